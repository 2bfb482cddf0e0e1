"""`calibrate --images`: null comparisons of real renders give rates within their intervals (several
seeds), a biased renderer is caught by the same figures, and the JSON and page say so."""
import json

import pytest

from harness.cli import main
from harness.engines.mitsuba import MitsubaEngine
from harness.engines.mcval import McvalEngine
from harness.images.calibration import calibrate_images
from tests.helpers.scaled_engine import Scaled


@pytest.fixture(scope="module")
def mitsuba():
    return MitsubaEngine()


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_null_comparisons_are_within_their_intervals(mitsuba, seed):
    cal = calibrate_images(McvalEngine(), mitsuba, per_kind=3, seed=seed, resolution=64)
    assert not cal.failed and len(cal.results) == 9
    assert cal.within, [b for b in cal.blocks() if not b["within"]]
    assert cal.sound and cal.to_json()["pass"]
    power = cal.power()
    assert set(power) == {"normals", "simple", "ao"}
    assert all(0 < v["global_bias_90"] < 0.3 for v in power.values())


@pytest.mark.slow
def test_a_biased_renderer_is_outside_the_interval(mitsuba):
    cal = calibrate_images(Scaled(1.05), mitsuba, per_kind=3, seed=0, resolution=64)
    blocks = {(b["kind"], b["scale"], b["comparison_level"]): b for b in cal.blocks()}
    assert blocks[("test-closed-form", "whole", 0.01)]["rejections"] == 3
    assert not blocks[("test-closed-form", "whole", 0.01)]["within"]
    assert blocks[("test-closed-form", "whole", 0.01)]["verdict"] == "liberal"
    assert blocks[("test-test", "whole", 0.01)]["within"]  # scaled on both sides: still a null pair
    assert not cal.within and not cal.sound and not cal.to_json()["pass"]


@pytest.mark.slow
def test_the_command_writes_its_figures_and_page(tmp_path):
    out = tmp_path / "results"
    assert main(["calibrate", "--images", "--comparisons", "2", "--out", str(out)]) == 0
    run = out / "calibration-latest"
    data = json.loads((run / "calibration.json").read_text())
    images = data["images"]
    assert images["comparisons"] == 6 and isinstance(images["false_alarm_rate"], float)
    assert "warps" not in data
    for block in images["blocks"]:
        assert isinstance(block["comparisons"], int) and isinstance(block["false_alarm_rate"], float)
    page = (run / "calibration.html").read_text()
    assert "Power at the validation" in page and "test-closed-form" in page
    # The next report links it.
    assert main(["images", "--only", "plane_point:normals", "--out", str(out)]) == 0
    assert "../calibration-latest/calibration.html" in (out / "latest" / "report.html").read_text()


def test_a_calibration_with_no_null_run_exits_3(tmp_path, capsys):
    out = tmp_path / "results"
    assert main(["calibrate", "--warps", "--only", "tent", "--seeds", "0", "--no-mitsuba", "--out", str(out)]) == 3
    payload = json.loads((out / "calibration-latest" / "calibration.json").read_text())
    # The tent's two checks without Mitsuba: chi2 and samples_vs_target.
    assert payload["verdict_reason"] == ("nothing was judged: null warp runs: --seeds 0 over 2 warp checks gave "
                                         "none")
    assert not payload["pass"] and f"FAIL {payload['verdict_reason']}" in capsys.readouterr().out
