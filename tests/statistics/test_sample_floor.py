"""harness.statistics.welch.sample_floor: a pixel whose few batches all missed a rare contribution borrows the
variance the better-sampled side predicts for it, and nothing else changes."""
import numpy as np
import pytest

from harness.comparison.compare import compare_batches
from harness.statistics.constants import MISSED_CONTRIBUTION
from harness.statistics.welch import BatchStats, sample_floor


def stats(var: float, k: int) -> BatchStats:
    return BatchStats(np.zeros((2, 2, 3)), np.full((2, 2, 3), var), k)


def test_a_missed_contribution_takes_the_prediction_and_its_dof():
    a, b = stats(1e-12, 8), stats(1e-6, 16)
    fa, fb = sample_floor(a, b, 32, 256)
    # sigma^2 / (K n): the 16 x 256-sample side predicts 16 * 256 / (8 * 32) = 16 times its variance here.
    assert np.allclose(fa.var_of_mean, 16e-6)
    assert np.all(fa.var_dof == 15)
    assert fb is b


def test_an_ordinary_variance_is_kept():
    a, b = stats(0.5 * 16e-6, 8), stats(1e-6, 16)  # half the prediction: well above MISSED_CONTRIBUTION
    assert MISSED_CONTRIBUTION < 0.5
    fa, _ = sample_floor(a, b, 32, 256)
    assert np.allclose(fa.var_of_mean, a.var_of_mean) and np.all(fa.var_dof == 7)


def test_the_better_sampled_side_is_never_changed_and_order_does_not_matter():
    a, b = stats(1e-6, 16), stats(1e-12, 8)
    fa, fb = sample_floor(a, b, 256, 32)
    assert fa is a and np.allclose(fb.var_of_mean, 16e-6)


@pytest.mark.parametrize("samples", [(None, 256), (32, None), (32, 64)])
def test_unknown_or_equal_sample_counts_change_nothing(samples):
    a, b = stats(1e-12, 16), stats(1e-6, 8)  # 16 x 32 = 8 x 64 samples in the last case
    assert sample_floor(a, b, *samples) == (a, b)


def _shadow_edge(rng, k: int, spp: int, hits: np.ndarray | None = None) -> np.ndarray:
    """(k, 16, 16, 3) batches of a flat 0.5 image with one pixel that a sliver covers: each batch's
    value there drops by 0.3 / spp per sample (of spp) that lands in it, probability 0.02."""
    out = 0.5 + 1e-3 * rng.standard_normal((k, 16, 16, 1)).repeat(3, axis=-1)
    count = rng.binomial(spp, 0.02, k) if hits is None else hits
    out[:, 5, 5, :] -= (0.3 * count / spp)[:, None]
    return out


def test_a_pixel_whose_batches_all_missed_a_sliver_passes_given_the_sample_counts():
    rng = np.random.default_rng(11)
    test = _shadow_edge(rng, 8, 32, hits=np.zeros(8, int))  # all 8 batches missed it (p = 0.52)
    reference = _shadow_edge(rng, 16, 256)
    without = compare_batches(test, reference)
    assert "pixel" in without.failed_scales and without.scales[0].worst == (5, 5)
    assert compare_batches(test, reference, samples=(32, 256)).passed


def test_a_pixel_truly_off_still_fails_given_the_sample_counts():
    rng = np.random.default_rng(12)
    test = _shadow_edge(rng, 8, 32)
    test[:, 5, 5, :] += 0.05  # a 10 % error in one pixel
    result = compare_batches(test, _shadow_edge(rng, 16, 256), samples=(32, 256))
    assert "pixel" in result.failed_scales and result.scales[0].worst == (5, 5)


def test_a_variance_at_exactly_the_threshold_is_kept_and_just_below_it_replaced():
    # The prediction for the 8 x 32-sample side from the 16 x 256-sample one is 16 times b's variance.
    prediction = 1.0 / 16.0 * (16 * 256) / (8 * 32)
    threshold = MISSED_CONTRIBUTION * prediction
    at = BatchStats(np.zeros(3), np.array([threshold, np.nextafter(threshold, 0.0), 2 * threshold]), 8)
    fa, _ = sample_floor(at, BatchStats(np.zeros(3), np.full(3, 1.0 / 16.0), 16), 32, 256)
    # "Only a variance below MISSED_CONTRIBUTION times the prediction is replaced."
    assert fa.var_of_mean[0] == threshold and fa.var_of_mean[2] == 2 * threshold
    assert fa.var_of_mean[1] == pytest.approx(prediction, rel=1e-12)
    assert list(fa.var_dof) == [7, 15, 7]


def test_the_floored_side_keeps_its_means_and_batch_count():
    rng = np.random.default_rng(13)
    mean = rng.normal(size=(2, 2, 3))
    a = BatchStats(mean, np.full((2, 2, 3), 1e-12), 8)
    fa, fb = sample_floor(a, stats(1e-6, 16), 32, 256)
    assert fa.mean is mean and fa.k == 8
    fb2, fa2 = sample_floor(stats(1e-6, 16), a, 256, 32)
    assert fa2.mean is mean and fa2.k == 8 and fb2.k == 16
