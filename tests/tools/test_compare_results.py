"""tools/compare_results.py: two results.json files agree when every verdict and string is equal and every
number shares --digits significant digits; each kind of difference is reported."""
import json

from tools.compare_results import compare, main

RUN = {"verdict": "PASS", "seconds": 3.0,
       "images": [{"scene": "plane", "integrator": "ao", "verdict": "PASS", "image_mean": [0.123456, 0.5],
                   "tests": {"mitsuba": {"tests": [{"scale": "image", "min_p": 0.4321}]}}},
                  {"scene": "cornell", "integrator": "ao", "verdict": "PASS", "image_mean": [1.0, 2.0]}]}


def _changed(**change) -> dict:
    run = json.loads(json.dumps(RUN))
    run["images"][0].update(change)
    return run


def test_the_same_run_in_another_order_and_time_agrees():
    other = json.loads(json.dumps(RUN))
    other["images"].reverse()
    other["seconds"] = 9.0
    other["images"][1]["image_mean"] = [0.1234564, 0.5]  # the same to 6 digits
    assert compare(RUN, other) == []


def test_a_changed_verdict_a_number_and_a_missing_field_are_differences():
    assert compare(RUN, _changed(verdict="FAIL")) == ["/images[plane/ao]/verdict: 'PASS' against 'FAIL'"]
    assert len(compare(RUN, _changed(image_mean=[0.123457, 0.5]))) == 1
    assert compare(RUN, _changed(image_mean=[0.123457, 0.5]), digits=5) == []
    gone = _changed()
    del gone["images"][0]["tests"]
    assert compare(RUN, gone) == ["/images[plane/ao]/tests: only in the first"]


def test_the_command_exits_1_on_a_difference(tmp_path, capsys):
    old, new = tmp_path / "old.json", tmp_path / "new.json"
    old.write_text(json.dumps(RUN))
    new.write_text(json.dumps(_changed(image_mean=[0.12346, 0.5])))
    assert main([str(old), str(new)]) == 1
    assert main([str(old), str(new), "--digits", "4"]) == 0
    assert "0 difference(s)" in capsys.readouterr().out.splitlines()[-1]
