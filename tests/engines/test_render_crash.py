"""A renderer that is killed, reports an error or hangs fails its case only: the run goes on and writes
every output, and results.json, junit.xml, report.html and the terminal say why."""
import json
import xml.etree.ElementTree as ET

import pytest

from harness.cli import main
from tests.helpers.render_wrappers import write_wrapper
from tests.helpers.registered_integrators import PRODUCT


def _run(tmp_path, monkeypatch, capsys, behaviour: str, target: str, timeout: str = "60") -> tuple[int, dict, str]:
    monkeypatch.setenv("MCVAL_RENDER", str(write_wrapper(tmp_path, behaviour, target)))
    monkeypatch.setenv("MCVAL_RENDER_TIMEOUT", timeout)
    out = tmp_path / "results"
    code = main(["images", "--only", "plane_point", "--out", str(out)])
    run = out / "latest"
    for name in ("results.json", "report.html", "junit.xml"):
        assert (run / name).exists(), name
    return code, json.loads((run / "results.json").read_text()), capsys.readouterr().out


def _check(code: int, results: dict, failed: str, reason: str, run, printed: str) -> None:
    assert code == 1
    assert results["pass"] is False
    entries = {e["integrator"]: e for e in results["images"]}
    assert set(entries) == set(PRODUCT)  # the other cases still ran
    bad = entries.pop(failed)
    assert bad["pass"] is False and bad["tests"] == {}
    assert bad["error"].startswith("mcval render: ") and reason in bad["error"]
    for other in entries.values():
        assert other["pass"] is True and other["error"] is None and other["tests"]
    suites = ET.parse(run / "junit.xml").getroot()
    failures = [(tc.get("classname"), tc.find("failure").get("message"))
                for tc in suites.iter("testcase") if tc.find("failure") is not None]
    assert len(failures) == 1 and failures[0][0] == f"mcval.{failed}" and reason in failures[0][1]
    page = (run / "report.html").read_text()
    assert "Render failed" in page and reason in page
    assert f"plane_point:{failed}" in printed and reason in printed.replace("\n", " ")


@pytest.mark.slow
def test_a_renderer_killed_mid_run_fails_its_case_and_the_run_goes_on(tmp_path, monkeypatch, capsys):
    code, results, printed = _run(tmp_path, monkeypatch, capsys, "kill", "simple")
    _check(code, results, "simple", "killed by signal SIGKILL (9)", tmp_path / "results" / "latest", printed)


@pytest.mark.slow
def test_a_scene_error_fails_its_case_with_the_message(tmp_path, monkeypatch, capsys):
    code, results, printed = _run(tmp_path, monkeypatch, capsys, "scene_error", "ao")
    _check(code, results, "ao", "exited with status 1: error: ", tmp_path / "results" / "latest", printed)
    (ao,) = [e for e in results["images"] if e["integrator"] == "ao"]
    assert 'expected an integer, got "twelve"' in ao["error"]


@pytest.mark.slow
def test_a_hung_renderer_is_ended_by_the_timeout(tmp_path, monkeypatch, capsys):
    code, results, printed = _run(tmp_path, monkeypatch, capsys, "hang", "normals", timeout="5")
    _check(code, results, "normals", "timed out after 5 s", tmp_path / "results" / "latest", printed)


@pytest.mark.parametrize("failing", ["mitsuba", "analytic"])
def test_a_reference_engine_that_raises_fails_its_case(tmp_path, monkeypatch, failing):
    import harness.images.case_renders as case_renders
    import harness.images.gather as gather

    def boom(*args, **kwargs):
        raise RuntimeError("the reference engine broke\nsecond line")

    if failing == "mitsuba":
        monkeypatch.setattr(gather, "load_reference", lambda case, engine: (None, "no stored reference"))
        monkeypatch.setattr(case_renders, "render_reference", boom)
    else:
        monkeypatch.setattr(case_renders.AnalyticEngine, "render", boom)
    out = tmp_path / "results"
    assert main(["images", "--only", "plane_point:ao", "--out", str(out)]) == 1
    entry = json.loads((out / "latest" / "results.json").read_text())["images"][0]
    prefix = "Mitsuba reference" if failing == "mitsuba" else "closed form"
    assert entry["pass"] is False and entry["error"] == f"{prefix}: the reference engine broke"
