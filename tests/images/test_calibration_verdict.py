"""The image calibration's verdict from its counts alone: a check that raises more false alarms than its
level fails it; one that raises fewer (conservative) is reported as such and passes; failed comparisons fail."""
from harness.images.calibration import ImageCalibration
from harness.comparison.compare import SCALES
from harness.images.null_task import BIASES, KINDS
from harness.statistics.calibration_rates import CALIBRATION_LEVELS


def _results(rejects) -> list[dict]:
    """80 null comparisons per kind; `rejects(level, i)` says whether comparison i rejects at `level`."""
    out = []
    for kind in KINDS:
        for i in range(80):
            rejected = {str(level): {**dict.fromkeys(SCALES, False), "whole": rejects(level, i)}
                        for level in CALIBRATION_LEVELS}
            r = {"kind": kind, "case": "x:simple", "integrator": "simple", "rejected": rejected, "image_min_p": 0.5}
            if kind == "test-test":
                r["global"] = r["tile"] = [b > 0.01 for b in BIASES]
            out.append(r)
    return out


def _verdicts(cal: ImageCalibration) -> set[str]:
    return {b["verdict"] for b in cal.blocks() if b["scale"] == "whole" and b["kind"] == "all"}


def test_rates_at_their_levels_are_within():
    cal = ImageCalibration(_results(lambda level, i: i < round(80 * level)), 1e-4, 1.0, [])
    assert _verdicts(cal) == {"within"} and cal.within and cal.sound and cal.to_json()["pass"]


def test_a_check_that_never_rejects_is_conservative_and_passes():
    cal = ImageCalibration(_results(lambda level, i: False), 1e-4, 1.0, [])
    verdicts = {b["comparison_level"]: b["verdict"] for b in cal.blocks() if b["scale"] == "whole" and b["kind"] == "all"}
    assert verdicts[0.3] == "conservative"
    assert not cal.within and cal.sound and cal.to_json()["pass"]


def test_a_check_that_rejects_too_often_fails():
    cal = ImageCalibration(_results(lambda level, i: i < round(80 * min(1.0, 2.5 * level))), 1e-4, 1.0, [])
    assert "liberal" in _verdicts(cal) and not cal.sound and not cal.to_json()["pass"]


def test_a_failed_comparison_fails_the_calibration():
    cal = ImageCalibration(_results(lambda level, i: i < round(80 * level)), 1e-4, 1.0, ["test-test x:simple: died"])
    assert not cal.sound and not cal.to_json()["pass"]
