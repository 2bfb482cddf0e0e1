"""Calibration of the warp checks: exact intervals, rates that flag a miscalibrated test, and the real run."""
import numpy as np
import pytest

from harness.statistics.calibration_rates import clopper_pearson, rates, uniformity_p
from harness.engines.base import Engine, WarpFunctions
from harness.warps.calibration import calibrate_warps, null_p_values
from harness.warps.suite import WarpSpec


def test_clopper_pearson_against_its_closed_forms():
    # k = 0: the upper end solves (1 - p)^n = (1 - c) / 2; k = n: the lower end solves p^n = (1 - c) / 2.
    lo, hi = clopper_pearson(0, 20, 0.95)
    assert lo == 0 and hi == pytest.approx(1 - 0.025 ** (1 / 20), rel=1e-9)
    lo, hi = clopper_pearson(20, 20, 0.95)
    assert hi == 1 and lo == pytest.approx(0.025 ** (1 / 20), rel=1e-9)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_uniform_p_values_are_within_and_skewed_ones_are_not(seed):
    p = np.random.default_rng(seed).random(2000)
    assert all(r.within for r in rates(p, intervals=3)) and uniformity_p(p) > 1e-3
    assert all(r.verdict == "within" and not r.liberal for r in rates(p, intervals=3))
    # A test that rejects too often (p squared: rate sqrt(level)) and one that rejects too rarely.
    assert all(r.verdict == "liberal" for r in rates(p ** 2, intervals=3))
    assert all(r.verdict == "conservative" and not r.liberal for r in rates(np.sqrt(p), intervals=3))


class _Wrong(Engine):
    """Our uniform disk with the seed document's pdf (pi instead of 1/pi), as an engine."""

    name = "wrong"

    def __init__(self, mcval):
        self._mcval = mcval

    def version(self) -> str:
        return "wrong disk"

    def warp(self, name, alpha=None):
        f = self._mcval.warp(name, alpha)
        return WarpFunctions(f.sample, lambda p: np.where((p ** 2).sum(1) <= 1, np.pi, 0.0), f.native_run)


def test_a_wrong_pdf_rejects_at_every_seed(mcval):
    p = null_p_values(WarpSpec("square_to_uniform_disk", "disk"), _Wrong(mcval), None, range(5), 100_000)
    assert np.all(p["chi2"] < 1e-6)


@pytest.mark.slow
def test_correct_warps_are_calibrated(mcval, mitsuba):
    """A short calibration (40 seeds, 100k samples) of three warps, with Mitsuba: every rate within."""
    specs = [WarpSpec("square_to_tent", "tent"), WarpSpec("square_to_cosine_hemisphere", "hemisphere"),
             WarpSpec("square_to_beckmann", "hemisphere", 0.05)]
    cal = calibrate_warps(mcval, mitsuba, specs, seeds=40, samples=100_000)
    assert cal.within, [(e.warp, e.check, [r.to_json() for r in e.rates]) for e in cal.entries if not e.within]
    assert {e.check for e in cal.pooled} == {"chi2", "samples_vs_target", "samples_vs_mitsuba"}
    assert all(len(e.p_values) == 40 for e in cal.entries)
    out = cal.to_json()
    assert out["pooled"][0]["comparisons"] == 120 and isinstance(out["pooled"][0]["false_alarm_rate"], float)
