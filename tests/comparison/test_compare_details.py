"""harness.comparison.compare's pieces (tile means, summaries, one scale's tests, the reports)
and harness.statistics.welch's, each against its definition or an independent computation (scipy, a loop)."""
import json

import numpy as np
import pytest
from scipy import stats as sps
from scipy.optimize import brentq

from harness.comparison.compare import (Comparison, ScaleTest, _noiseless, _scale_test, compare_batches,
                                        compare_summaries)
from harness.comparison.summary import summarize, tile_means
from harness.statistics.constants import sidak_level
from harness.statistics.welch import BatchStats, welch_p_values


def welch_by_scipy(a: BatchStats, b: BatchStats) -> np.ndarray:
    """Welch's two-sided p-values from the means and variances of the means (no rounding floor)."""
    return sps.ttest_ind_from_stats(a.mean, np.sqrt(a.var_of_mean * a.k), a.k,
                                    b.mean, np.sqrt(b.var_of_mean * b.k), b.k, equal_var=False).pvalue


def random_stats(rng, shape, k, spread=1.0, var=1e-4) -> BatchStats:
    return BatchStats(0.5 + spread * 1e-2 * rng.standard_normal(shape), var * rng.uniform(0.5, 2.0, shape), k)


# --- tile_means and summarize ---------------------------------------------------------------------------------

def test_tile_means_average_what_each_tile_holds():
    rng = np.random.default_rng(20)
    x = rng.uniform(size=(2, 10, 13, 3))
    got = tile_means(x, 4)
    assert got.shape == (2, 3, 4, 3)
    for r in range(3):
        for c in range(4):
            block = x[:, 4 * r: 4 * r + 4, 4 * c: 4 * c + 4]
            np.testing.assert_allclose(got[:, r, c], block.mean(axis=(1, 2)), rtol=1e-12)


def test_summarize_follows_its_definition():
    rng = np.random.default_rng(21)
    x = rng.uniform(-0.5, 1.0, size=(5, 9, 7, 3))
    s = summarize(x, tile=4)
    k = x.shape[0]
    np.testing.assert_allclose(s.pixel.mean, x.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(s.pixel.var_of_mean, x.var(axis=0, ddof=1) / k, rtol=1e-12)
    image = np.array([x[i].reshape(-1, 3).mean(axis=0) for i in range(k)])
    np.testing.assert_allclose(s.image.mean, image.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(s.image.var_of_mean, image.var(axis=0, ddof=1) / k, rtol=1e-12)
    tile = np.array([[[x[i, 4 * r: 4 * r + 4, 4 * c: 4 * c + 4].reshape(-1, 3).mean(axis=0) for c in range(2)]
                      for r in range(3)] for i in range(k)])
    np.testing.assert_allclose(s.tile.mean, tile.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(s.tile.var_of_mean, tile.var(axis=0, ddof=1) / k, rtol=1e-12)
    assert s.minimum.shape == (9, 7, 3)
    np.testing.assert_array_equal(s.minimum, x.min(axis=0))
    assert s.tile_size == 4 and s.pixel.k == s.tile.k == s.image.k == k


def test_summarize_works_in_float64_whatever_the_input():
    rng = np.random.default_rng(22)
    x = rng.uniform(0.1, 10.0, size=(4, 64, 64, 3)).astype(np.float32)
    s = summarize(x)
    exact = x.astype(np.float64)
    np.testing.assert_allclose(s.image.mean, exact.mean(axis=(1, 2)).mean(axis=0), rtol=1e-13)
    assert s.minimum.dtype == np.float64


def test_summarize_takes_two_batches_and_rejects_fewer_or_other_shapes():
    s = summarize(np.stack([np.zeros((1, 1, 3)), np.ones((1, 1, 3))]), tile=1)
    np.testing.assert_allclose(s.pixel.var_of_mean, 0.25)  # var([0, 1], ddof=1) / 2
    with pytest.raises(ValueError, match="at least 2 batches"):
        summarize(np.zeros((1, 4, 4, 3)))
    with pytest.raises(ValueError, match=r"\(2, 4, 4, 4\)"):
        summarize(np.zeros((2, 4, 4, 4)))
    with pytest.raises(ValueError, match=r"\(2, 4, 3\)"):
        summarize(np.zeros((2, 4, 3)))


def test_a_negative_value_in_one_batch_fails_even_when_the_mean_is_positive():
    x = np.full((4, 8, 8, 3), 0.5) + 1e-3 * np.random.default_rng(23).standard_normal((4, 8, 8, 3))
    y = x[::-1].copy()
    x[0, 2, 3, 1] = -0.2  # mean there is still positive
    assert x.mean(axis=0)[2, 3, 1] > 0
    result = compare_summaries(summarize(x), summarize(y))
    assert not result.finite.passed and not result.passed
    assert compare_summaries(summarize(x), summarize(y), signed=True).finite.passed


# --- one scale's tests -----------------------------------------------------------------------------------------

def test_scale_test_p_values_map_worst_and_failures():
    rng = np.random.default_rng(24)
    shape = (5, 3, 3)  # more rows than columns
    a, b = random_stats(rng, shape, 8), random_stats(rng, shape, 16)
    a.mean[3, 1, 2] += 0.2  # clearly off: the smallest p-value, at row 3, column 1
    noiseless = np.zeros(shape, bool)
    test, _ = _scale_test("tile", a, b, noiseless, 0.01, (10, 6), 2, 0.0, 0.0, 0.0)
    p = welch_by_scipy(a, b)
    assert test.tests == p.size
    assert test.min_p == pytest.approx(p.min(), rel=1e-9)
    assert test.worst == (6, 2)  # in pixels: the tile's top-left corner
    expected_map = np.repeat(np.repeat(p.min(axis=-1), 2, axis=0), 2, axis=1)
    np.testing.assert_allclose(test.p_map, expected_map, rtol=1e-9)
    # 45 independent exact tests: Sidak's level, and a failure for each p-value below it.
    assert test.level == pytest.approx(sidak_level(0.01, p.size), rel=1e-6)
    assert test.failures == np.count_nonzero(p < test.level) >= 1


def test_scale_test_crops_its_map_and_fills_one_that_cannot_be_upsampled():
    rng = np.random.default_rng(25)
    a, b = random_stats(rng, (3, 2, 3), 8), random_stats(rng, (3, 2, 3), 8)
    p = welch_by_scipy(a, b)
    cropped, _ = _scale_test("tile", a, b, np.zeros((3, 2, 3), bool), 0.01, (5, 3), 2, 0.0, 0.0, 0.0)
    np.testing.assert_allclose(cropped.p_map, np.repeat(np.repeat(p.min(axis=-1), 2, 0), 2, 1)[:5, :3], rtol=1e-9)
    filled, _ = _scale_test("tile", a, b, np.zeros((3, 2, 3), bool), 0.01, (7, 5), 2, 0.0, 0.0, 0.0)
    assert filled.p_map.shape == (7, 5)
    np.testing.assert_allclose(filled.p_map, p.min(), rtol=1e-9)


def test_scale_test_uses_its_rounding_and_scale():
    rng = np.random.default_rng(26)
    a, b = random_stats(rng, (4, 4, 3), 8, var=1e-14), random_stats(rng, (4, 4, 3), 8, var=1e-14)
    exact, _ = _scale_test("pixel", a, b, np.zeros((4, 4, 3), bool), 0.01, (4, 4), 1, 0.0, 0.0, 0.0)
    assert exact.min_p == pytest.approx(welch_by_scipy(a, b).min(), rel=1e-9)
    floored, _ = _scale_test("pixel", a, b, np.zeros((4, 4, 3), bool), 0.01, (4, 4), 1, 2.0, 1e-5, 0.0)
    p, _, _ = welch_p_values(a, b, 2.0, 1e-5)
    assert floored.min_p == pytest.approx(p.min(), rel=1e-9)


def test_a_non_finite_element_is_a_certain_rejection_and_counts_as_one_test():
    rng = np.random.default_rng(27)
    a, b = random_stats(rng, (4, 4, 3), 8), random_stats(rng, (4, 4, 3), 8)
    a.mean[1, 2, 0] = np.nan
    test, _ = _scale_test("pixel", a, b, np.zeros((4, 4, 3), bool), 0.01, (4, 4), 1, 0.0, 0.0, 0.0)
    assert test.min_p == 0.0 and test.worst == (1, 2) and test.failures >= 1
    assert test.level == pytest.approx(sidak_level(0.01, 48), rel=1e-6)


def test_noiseless_elements_and_elements_without_noise_do_not_count():
    rng = np.random.default_rng(28)
    a, b = random_stats(rng, (4, 4, 3), 8), random_stats(rng, (4, 4, 3), 8)
    noiseless = np.zeros((4, 4, 3), bool)
    noiseless[:2] = True  # told noiseless (before moderation), though they have noise here
    a.var_of_mean[2, 0], b.var_of_mean[2, 0] = 0.0, 0.0  # no noise on either side, not told
    test, _ = _scale_test("pixel", a, b, noiseless, 0.01, (4, 4), 1, 0.0, 0.0, 0.0)
    assert test.level == pytest.approx(sidak_level(0.01, 48 - 24 - 3), rel=1e-6)
    assert test.tests == 48


def test_tests_shrunk_by_the_rounding_floor_count_by_their_inflation():
    rng = np.random.default_rng(29)
    shape = (4, 4, 3)
    a, b = random_stats(rng, shape, 8, var=1e-11), random_stats(rng, shape, 8, var=1e-11)
    test, _ = _scale_test("pixel", a, b, np.zeros(shape, bool), 0.01, (4, 4), 1, 0.0, 1e-5, 0.0)
    # Each test rejects at P(|t(dof)| / inflation > crit), inflation = se / noise-only se.
    noise = np.sqrt(a.var_of_mean + b.var_of_mean)
    floor = 1e-5 * 0.5 * (np.abs(a.mean) + np.abs(b.mean))
    inflation = np.sqrt(noise**2 + floor**2) / noise
    assert inflation.min() > 1.2
    dof = (a.var_of_mean + b.var_of_mean) ** 2 / (a.var_of_mean**2 / 7 + b.var_of_mean**2 / 7)

    def family(level):
        rates = 2 * sps.t.sf(sps.t.isf(level / 2, dof) * inflation, dof)
        return 1 - np.prod(1 - rates)

    expected = brentq(lambda lv: family(lv) - 0.01, 1e-9, 0.01, xtol=1e-14)
    assert test.level == pytest.approx(expected, rel=1e-3)


def test_one_set_of_statistics_estimates_its_channel_correlation_from_live_elements():
    rng = np.random.default_rng(30)
    shape = (600, 3)
    a, b = random_stats(rng, shape, 8), random_stats(rng, shape, 8)
    # 200 noiseless elements whose channels all disagree alike (t far out, the same in every channel).
    a.mean[:200], b.mean[:200] = 0.5, 0.6
    a.var_of_mean[:200], b.var_of_mean[:200] = 0.0, 0.0
    noiseless = np.zeros(shape, bool)
    noiseless[:200] = True
    test, rho = _scale_test("tile", a, b, noiseless, 0.01, (1, 1), 1, 0.0, 1e-5)
    assert rho == 0.0  # the live elements' channels are independent
    assert test.level == pytest.approx(sidak_level(0.01, 400 * 3), rel=1e-6)
    # Channels that are the same statistic count once.
    same_a = BatchStats(np.repeat(a.mean[200:, :1], 3, 1), np.repeat(a.var_of_mean[200:, :1], 3, 1), 8)
    same_b = BatchStats(np.repeat(b.mean[200:, :1], 3, 1), np.repeat(b.var_of_mean[200:, :1], 3, 1), 8)
    test, rho = _scale_test("tile", same_a, same_b, np.zeros((400, 3), bool), 0.01, (1, 1), 1, 0.0, 0.0)
    assert rho == 1.0 and test.level == pytest.approx(sidak_level(0.01, 400), rel=1e-3)


def test_one_vector_of_statistics_takes_its_channels_as_independent():
    rng = np.random.default_rng(31)
    a, b = random_stats(rng, (3,), 8), random_stats(rng, (3,), 8)
    test, rho = _scale_test("image", a, b, np.zeros(3, bool), 0.01, (4, 5), 5, 0.0, 0.0)
    assert rho == 0.0 and test.level == pytest.approx(sidak_level(0.01, 3), rel=1e-6)
    p = welch_by_scipy(a, b)
    np.testing.assert_allclose(test.p_map, np.full((4, 5), p.min()), rtol=1e-9)
    assert test.worst == (0, 0) and test.tests == 3


def test_a_p_value_equal_to_the_level_is_not_a_rejection():
    a = BatchStats(np.array([0.5]), np.array([1e-4]), 8)
    b = BatchStats(np.array([0.51]), np.array([2e-4]), 8)
    p = float(welch_by_scipy(a, b)[0])
    test, _ = _scale_test("image", a, b, np.zeros(1, bool), p, (1, 1), 1, 0.0, 0.0, 0.0)
    assert test.level == p and test.min_p == pytest.approx(p, rel=1e-12)
    assert test.failures == int(test.min_p < test.level)


def test_noiseless_means_constant_on_both_sides():
    a = BatchStats(np.zeros(4), np.array([0.0, 0.0, 1.0, 1.0]), 4)
    b = BatchStats(np.zeros(4), np.array([0.0, 1.0, 0.0, 1.0]), 4)
    assert list(_noiseless(a, b)) == [True, False, False, False]


# --- compare_summaries and the reports ---------------------------------------------------------------------------

def test_a_comparison_reports_what_its_scales_found():
    rng = np.random.default_rng(33)
    t = 0.5 + 0.01 * rng.standard_normal((8, 16, 16, 3))
    r = 0.5 + 0.01 * rng.standard_normal((12, 16, 16, 3))
    t[:, 4:8, 8:12] += 0.05
    result = compare_batches(t, r)
    assert result.batches == (8, 12)
    assert [s.scale for s in result.scales] == ["pixel", "tile", "image"]
    assert not result.passed and "pixel" in result.failed_scales and result.failed_checks == result.failed_scales
    doc = json.loads(json.dumps(result.to_json()))
    assert doc["pass"] is False and doc["batches"] == [8, 12]
    assert doc["detectable_bias"] == result.detectable_bias
    assert doc["detectable_tile_bias"] == result.detectable_tile_bias
    assert doc["finite"] == result.finite.to_json() and doc["metrics"] == result.metrics
    for got, scale in zip(doc["tests"], result.scales):
        assert got == {"scale": scale.scale, "tests": scale.tests, "level": scale.level, "min_p": scale.min_p,
                       "failures": scale.failures, "worst": list(scale.worst), "pass": scale.failures == 0}
    assert isinstance(result.scales[0], ScaleTest) and isinstance(result, Comparison)

