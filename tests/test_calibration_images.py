"""The image comparison rejects a correct renderer at its stated rate, and finds `detectable_bias` half of
the time: seeded synthetic null pairs (heteroscedastic Gaussian pixels, K = 8 against 16 batches) through
`compare_summaries`. tests/image_calibration.py measures the same at more replications and on renders."""
import numpy as np
import pytest
from scipy import stats as sps

from harness.compare import SCALES
from harness.stats import sidak_level
from tests.image_calibration import detection_rate, null_rates, synthetic_pairs

RUNS = 120


@pytest.fixture(scope="module")
def pairs():
    draw = synthetic_pairs(1, size=24)
    return [draw() for _ in range(RUNS)]


def acceptance(rate: float, runs: int, tail: float = 5e-4) -> tuple[float, float]:
    """Rejection fractions a test at `rate` gives in `runs` runs but for a `tail` chance at either end."""
    return sps.binom.ppf(tail, runs, rate) / runs, sps.binom.isf(tail, runs, rate) / runs


def test_whole_comparison_rejects_at_its_level(pairs):
    rates = null_rates(pairs, 0.3)
    assert 0.2 <= rates.rate() <= 0.4, rates
    per_scale = sidak_level(0.3, len(SCALES))
    lo, hi = acceptance(per_scale, RUNS)
    for scale in SCALES:
        assert lo <= rates.rate(scale) <= hi, (scale, rates)


def test_few_false_alarms_at_the_validation_level(pairs):
    rates = null_rates(pairs, 0.01)
    assert rates.rate() <= 0.025 + 1e-12, rates


def test_detectable_bias_is_found_half_of_the_time():
    draw = synthetic_pairs(2, size=24)
    rate, runs, bias = detection_rate((draw() for _ in range(80)), draw)
    assert 0 < bias < 0.05
    assert 0.3 <= rate <= 0.7, rate
