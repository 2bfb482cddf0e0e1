"""The whole-image variance test: at its level on null pairs of binary and Gaussian estimates (the kinds
where an F-test per pixel is not), with the power it states, and blind to float rounding."""
import numpy as np
import pytest
from scipy.stats import binomtest

from harness.statistics.variance_ratio import variance_ratio
from harness.statistics.welch import BatchStats


def _occlusion_field(seed, size):
    """Per-pixel visibility, a band fully visible and one fully hidden (no noise there), a tinted channel."""
    p = np.random.default_rng(seed).random((size, size, 1)) * np.ones((1, 1, 3))
    p[: size // 4] = 1.0
    p[:, : size // 8] = 0.0
    p[..., 0] *= 0.9
    return p


def _binary(rng, p, k, n):
    return BatchStats.of(rng.binomial(n, p, size=(k,) + p.shape) / n)


def _gaussian(rng, sd, k, n):
    return BatchStats.of(1.0 + rng.normal(size=(k,) + sd.shape) * sd / np.sqrt(n))


def _null_p(kind, i, rng, size=64):
    p = _occlusion_field(1000 + i, size)
    if kind == "binary":  # mcval (8 x 32 spp) against a reference of 16 x 256, as the image suite
        return variance_ratio(_binary(rng, p, 8, 32), _binary(rng, p, 16, 256), (32, 256), 0.05).p_value
    sd = 0.1 + p
    return variance_ratio(_gaussian(rng, sd, 8, 32), _gaussian(rng, sd, 8, 32), (32, 32), 0.05).p_value


@pytest.mark.parametrize("kind", ["binary", "gaussian"])
def test_null_pairs_reject_at_the_level(kind):
    rng = np.random.default_rng(7)
    p = np.array([_null_p(kind, i, rng) for i in range(200)])
    for level in (0.3, 0.05):
        rejected = int(np.sum(p < level))
        assert binomtest(rejected, p.size, level).pvalue > 0.01, (level, rejected)


def test_a_planted_ratio_is_found_as_often_as_stated():
    rng = np.random.default_rng(5)
    p = _occlusion_field(7, 64)
    stated = variance_ratio(_binary(rng, p, 8, 32), _binary(rng, p, 16, 256), (32, 256), 0.01)
    assert 1.0 < stated.found_half < stated.found_most < 1.1
    for ratio, power in ((stated.found_half, 0.5), (stated.found_most, 0.9)):
        found = 0
        for _ in range(120):
            b = rng.binomial(32, p, size=(8,) + p.shape) / 32
            m = b.mean(axis=0)
            planted = BatchStats.of(m + np.sqrt(ratio) * (b - m))  # the variance times `ratio`, the mean kept
            found += variance_ratio(planted, _binary(rng, p, 16, 256), (32, 256), 0.01).rejects
        assert binomtest(found, 120, power).pvalue > 0.01, (ratio, power, found)


def test_a_larger_and_a_smaller_variance_are_both_found():
    rng = np.random.default_rng(2)
    p = _occlusion_field(3, 64)
    b = rng.binomial(32, p, size=(8,) + p.shape) / 32
    m = b.mean(axis=0)
    for factor in (1.3, 0.7):
        r = variance_ratio(BatchStats.of(m + np.sqrt(factor) * (b - m)), _binary(rng, p, 16, 256), (32, 256), 0.01)
        assert r.rejects and r.ratio == pytest.approx(factor, rel=0.1)


def test_float_rounding_is_no_variance():
    exact = np.full((8, 32, 32, 3), 0.5)
    rounded = exact * (1 + 1e-7 * np.random.default_rng(1).standard_normal(exact.shape))
    assert variance_ratio(BatchStats.of(exact), BatchStats.of(rounded), (32, 256), 0.01) is None  # nothing varies


def test_too_small_an_image_is_not_tested():
    rng = np.random.default_rng(1)
    p = _occlusion_field(1, 16)  # 4 tiles
    assert variance_ratio(_binary(rng, p, 8, 32), _binary(rng, p, 16, 256), (32, 256), 0.01) is None
