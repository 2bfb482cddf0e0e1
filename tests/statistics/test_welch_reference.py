"""The harness's statistics against independent implementations and their definitions.

Welch's t-test and the chi-square tests against scipy, the Sidak levels (and their split in
`compare_batches`) against 1 - (1 - alpha)^(1/n), PSNR against 10 log10(peak^2 / MSE), the
efficiency ratio on a bench with a known answer. Fast: these run for every mutant in `make mutate`.
"""
import numpy as np
import pytest
from scipy import stats as sps
from scipy.optimize import brentq
from scipy.special import polygamma

from harness.bench.ladder import Curve, Step
from harness.bench.run import CaseBench
from harness.statistics.chi2 import goodness_of_fit, goodness_of_fit_batch, homogeneity
from harness.comparison.compare import compare_batches
from harness.comparison.metrics import image_metrics
from harness.statistics.constants import MIN_EXPECTED, ROUNDING_TOLERANCE, SIGNIFICANCE, sidak_level
from harness.statistics.welch import BatchStats, critical_t, moderate, prior_dof, welch_dof, welch_p_values


def definition_sidak(alpha, n):
    return 1.0 - (1.0 - alpha) ** (1.0 / n)


# --- Welch ------------------------------------------------------------------------------------------

WELCH_CASES = [  # (seed, K1, K2, sigma1, sigma2, shift)
    (0, 4, 12, 1.0, 3.0, 0.0),
    (1, 8, 8, 0.2, 2.0, 0.5),
    (2, 16, 5, 5.0, 0.5, 1.0),
    (3, 3, 30, 1.0, 1.0, 0.3),
    (4, 6, 9, 0.01, 0.03, 0.02),
]


@pytest.mark.parametrize("seed, k1, k2, s1, s2, shift", WELCH_CASES)
def test_welch_p_values_match_scipy(seed, k1, k2, s1, s2, shift):
    rng = np.random.default_rng(seed)
    a = rng.normal(shift, s1, (k1, 50))
    b = rng.normal(0.0, s2, (k2, 50))
    p, t, se = welch_p_values(BatchStats.of(a), BatchStats.of(b), scale=0.0, rounding=0.0)
    ref = sps.ttest_ind(a, b, equal_var=False, axis=0)
    np.testing.assert_allclose(t, ref.statistic, rtol=1e-10)
    np.testing.assert_allclose(p, ref.pvalue, rtol=1e-8, atol=1e-300)
    np.testing.assert_allclose(se, np.sqrt(a.var(0, ddof=1) / k1 + b.var(0, ddof=1) / k2), rtol=1e-12)
    # Two-sided: twice the smaller one-sided p-value, never the one-sided one.
    greater = sps.ttest_ind(a, b, equal_var=False, axis=0, alternative="greater").pvalue
    less = sps.ttest_ind(a, b, equal_var=False, axis=0, alternative="less").pvalue
    np.testing.assert_allclose(p, 2 * np.minimum(greater, less), rtol=1e-8)
    assert np.all(p > np.minimum(greater, less))


def test_welch_uses_satterthwaite_dof_and_t_tails():
    # Very unequal K and variances: the Welch-Satterthwaite dof (about 3) is far from the pooled one (32),
    # and the t tail far from the normal one.
    a = np.array([[0.0], [1.0], [2.0], [3.0]]) * 3.0
    b = np.linspace(-0.1, 0.1, 30)[:, None] + 1.0
    p, t, _ = welch_p_values(BatchStats.of(a), BatchStats.of(b), scale=0.0, rounding=0.0)
    ref = sps.ttest_ind(a, b, equal_var=False, axis=0)
    va, vb = a.var(0, ddof=1) / 4, b.var(0, ddof=1) / 30
    dof = (va + vb) ** 2 / (va**2 / 3 + vb**2 / 29)
    assert dof[0] < 4
    assert p[0] == pytest.approx(float(ref.pvalue[0]), rel=1e-9)
    assert p[0] == pytest.approx(float(2 * sps.t.sf(abs(t[0]), dof[0])), rel=1e-9)
    assert p[0] != pytest.approx(float(2 * sps.norm.sf(abs(t[0]))), rel=0.05)
    assert p[0] != pytest.approx(float(2 * sps.t.sf(abs(t[0]), 32)), rel=0.05)


def test_critical_t_is_the_two_sided_quantile():
    for level, dof in [(0.01, 14), (1e-5, 5), (0.3, 30)]:
        c = critical_t(level, dof)
        assert 2 * sps.t.sf(c, dof) == pytest.approx(level, rel=1e-9)


def test_welch_standard_error_floor_and_degenerate_inputs():
    rng = np.random.default_rng(5)
    a, b = rng.normal(1.0, 0.1, (6, 20)), rng.normal(-2.0, 0.3, (9, 20))
    sa, sb = BatchStats.of(a), BatchStats.of(b)
    rounding, scale = 1e-2, 3.0
    p, t, se = welch_p_values(sa, sb, scale=scale, rounding=rounding)
    floor = rounding * (0.5 * (np.abs(a.mean(0)) + np.abs(b.mean(0))) + scale)
    expected_se = np.sqrt(a.var(0, ddof=1) / 6 + b.var(0, ddof=1) / 9 + floor**2)
    np.testing.assert_allclose(se, expected_se, rtol=1e-12)
    np.testing.assert_allclose(t, (a.mean(0) - b.mean(0)) / expected_se, rtol=1e-12)
    va, vb = a.var(0, ddof=1) / 6, b.var(0, ddof=1) / 9
    dof = (va + vb) ** 2 / (va**2 / 5 + vb**2 / 8)
    np.testing.assert_allclose(p, 2 * sps.t.sf(np.abs(t), dof), rtol=1e-9)
    # Defaults: no image scale, float32 rounding.
    default = welch_p_values(sa, sb)
    explicit = welch_p_values(sa, sb, scale=0.0, rounding=ROUNDING_TOLERANCE)
    for x, y in zip(default, explicit):
        np.testing.assert_array_equal(x, y)
    assert not np.allclose(welch_p_values(sa, sb, scale=1.0)[2], explicit[2], rtol=1e-9, atol=0)
    # Both sides constant and equal: p = 1; constant and different (no floor): p = 0; NaN: NaN.
    const = BatchStats(np.array([2.0, 2.0, np.nan]), np.zeros(3), 4)
    other = BatchStats(np.array([2.0, 3.0, 2.0]), np.zeros(3), 4)
    p, t, _ = welch_p_values(const, other, scale=0.0, rounding=0.0)
    assert p[0] == 1.0 and t[0] == 0.0
    assert np.isnan(p[2]) and np.isnan(t[2])
    p, _, _ = welch_p_values(other, other, scale=np.inf, rounding=1e-5)
    assert np.all(np.isnan(p))


def test_welch_uses_the_variances_own_dof():
    """Moderated variances carry their own degrees of freedom into Welch-Satterthwaite."""
    mean_a, mean_b = np.array([1.0, 0.0, 5.0]), np.array([0.2, 0.5, 4.0])
    va, vb = np.array([0.04, 0.01, 0.3]), np.array([0.02, 0.05, 0.1])
    da, db = np.array([7.0, 30.0, 3.0]), np.array([40.0, 7.0, 3.0])
    a, b = BatchStats(mean_a, va, 8, da), BatchStats(mean_b, vb, 8, db)
    p, t, _ = welch_p_values(a, b, scale=0.0, rounding=0.0)
    dof = (va + vb) ** 2 / (va**2 / da + vb**2 / db)
    np.testing.assert_allclose(t, (mean_a - mean_b) / np.sqrt(va + vb), rtol=1e-12)
    np.testing.assert_allclose(p, 2 * sps.t.sf(np.abs(t), dof), rtol=1e-9)
    assert BatchStats(mean_a, va, 8).var_dof == 7.0


def test_welch_dof_in_its_corner_cases():
    m = np.zeros(1)
    # Both variances 0: the summed variance dofs (K1 + K2 - 2 unless moderated).
    assert welch_dof(BatchStats(m, np.zeros(1), 5), BatchStats(m, np.zeros(1), 9))[0] == 12.0
    zero_a, zero_b = BatchStats(m, np.zeros(1), 8, np.array([20.0])), BatchStats(m, np.zeros(1), 8, np.array([30.0]))
    assert welch_dof(zero_a, zero_b)[0] == 50.0
    # A NaN variance, or an infinite one (inf / inf): K1 + K2 - 2.
    assert welch_dof(BatchStats(m, np.full(1, np.nan), 5), BatchStats(m, np.ones(1), 9))[0] == 12.0
    assert welch_dof(BatchStats(m, np.full(1, np.inf), 5, np.array([30.0])), BatchStats(m, np.ones(1), 9))[0] == 12.0
    # Between 1 and 2, kept; below 1, raised to 1.
    one, tenth = BatchStats(m, np.ones(1), 2), BatchStats(m, np.full(1, 0.1), 2)
    assert welch_dof(one, tenth)[0] == pytest.approx(1.1**2 / 1.01, rel=1e-12)
    assert welch_dof(BatchStats(m, np.ones(1), 2, np.array([0.5])), BatchStats(m, np.zeros(1), 2))[0] == 1.0


def test_critical_t_keeps_the_shape_of_its_dof():
    assert type(critical_t(0.01, 14)) is float
    c = critical_t(0.01, np.array([5.0, 14.0]))
    assert c.shape == (2,)
    np.testing.assert_allclose(c, sps.t.isf(0.005, [5.0, 14.0]), rtol=1e-12)


def _log_ratios(variance, n=40):
    return np.sqrt(variance) * np.where(np.arange(n) % 2, 1.0, -1.0)  # np.var of these is `variance`


@pytest.mark.parametrize("d0", [0.5, 20.0, 40.0])
def test_prior_dof_solves_its_moment_equation(d0):
    d, cap = 7.0, 56.0
    excess = float(polygamma(1, d0 / 2))
    ratios = _log_ratios(excess + float(polygamma(1, d / 2)))
    assert prior_dof(ratios, d, cap) == pytest.approx(d0, rel=1e-6)


def test_prior_dof_needs_ten_ratios_and_caps():
    assert prior_dof(_log_ratios(10.0, 9), 7.0, 56.0) == 0.0
    assert prior_dof(_log_ratios(0.0, 10), 7.0, 56.0) == 56.0
    assert prior_dof(_log_ratios(0.0, 10), 7.0, 30.0) == 30.0


def _moderate_by_definition(v, k, window=3):
    """Smyth's moderation written out element by element (edges replicated, as scipy's 'nearest')."""
    h, w, c = v.shape
    d = k - 1.0
    r = window // 2
    padded = np.pad(v, ((r, r), (r, r), (0, 0)), mode="edge")
    prior = np.zeros_like(v)
    for i in range(h):
        for j in range(w):
            block = padded[i:i + window, j:j + window]
            prior[i, j] = (block.sum(axis=(0, 1)) - v[i, j]) / (window * window - 1)
    ratio = np.log(v / prior)
    cap = (window * window - 1) * d
    excess = np.var(ratio) - float(polygamma(1, d / 2))
    if excess <= polygamma(1, cap / 2):
        d0 = cap
    else:
        d0 = brentq(lambda x: polygamma(1, x / 2) - excess, 1e-6, cap)
    # The neighbours' mean is E[sigma^2] = s0^2 d0 / (d0 - 2) under the prior; its scale s0^2 is what is pooled.
    s0 = prior * (d0 - 2) / d0 if d0 > 2 else prior
    return (d0 * s0 + d * v) / (d0 + d), d + d0


@pytest.mark.parametrize("spread, shape", [(0.0, (10, 12, 3)), (0.3, (10, 12, 3)), (1.5, (10, 12, 3)),
                                           (0.3, (2, 9, 3)), (0.3, (6, 7, 1))])
def test_moderated_variances_follow_their_definition(spread, shape):
    rng = np.random.default_rng(11)
    k = 8
    true_var = 0.01 * np.exp(spread * rng.standard_normal(shape))
    batches = rng.normal(0.0, np.sqrt(true_var), (k, *shape)) + 1.0
    stats = BatchStats.of(batches)
    moderated = moderate(stats)
    expected, dof = _moderate_by_definition(stats.var_of_mean, k)
    np.testing.assert_allclose(moderated.var_of_mean, expected, rtol=1e-9)
    np.testing.assert_allclose(moderated.var_dof, dof, rtol=1e-9)
    np.testing.assert_array_equal(moderated.mean, stats.mean)


def test_moderation_keeps_a_variance_whose_neighbours_are_all_zero():
    """As moderate's docstring says: its own variance and K - 1 degrees of freedom."""
    v = np.random.default_rng(2).uniform(0.005, 0.02, (9, 9, 3))
    v[2:7, 2:7, 0] = 0.0
    v[4, 4, 0] = 0.01
    moderated = moderate(BatchStats(np.ones((9, 9, 3)), v, 8))
    assert moderated.var_of_mean[4, 4, 0] == 0.01 and moderated.var_dof[4, 4, 0] == 7.0


def test_moderation_keeps_what_it_cannot_moderate():
    v = np.full((6, 6, 3), 0.01)
    v[2, 3, 1] = np.nan
    stats = BatchStats(np.ones((6, 6, 3)), v, 8)
    moderated = moderate(stats)
    assert np.isnan(moderated.var_of_mean[2, 3, 1])
    assert moderated.var_dof[2, 3, 1] == 7.0
    # A missed contribution (variance 0 amid non-zero neighbours) gets its neighbours' variance.
    v = np.full((6, 6, 3), 0.01)
    v[3, 3, 0] = 0.0
    moderated = moderate(BatchStats(np.ones((6, 6, 3)), v, 8))
    assert moderated.var_of_mean[3, 3, 0] > 0.005
    # Too few variances to estimate the prior's weight (< 10): unchanged.
    few = BatchStats(np.ones((2, 2, 2)), np.random.default_rng(3).uniform(0.01, 0.02, (2, 2, 2)), 8)
    assert moderate(few) is few
    # An image-scale statistic (3,) and one-pixel-wide images are left alone.
    image = BatchStats(np.ones(3), np.full(3, 0.01), 8)
    assert moderate(image) is image
    thin = BatchStats(np.ones((1, 9, 3)), np.full((1, 9, 3), 0.01), 8)
    assert moderate(thin) is thin


# --- chi-square -------------------------------------------------------------------------------------

@pytest.mark.parametrize("seed, cells", [(0, 10), (1, 51 * 51), (2, 3)])
def test_goodness_of_fit_matches_scipy(seed, cells):
    rng = np.random.default_rng(seed)
    probs = rng.uniform(0.5, 2.0, cells)
    probs /= probs.sum()
    n = 200 * cells
    observed = rng.multinomial(n, probs)
    expected = probs * n
    mcval = goodness_of_fit(observed, expected)
    ref = sps.chisquare(observed, expected)
    assert mcval.dof == cells - 1
    assert mcval.pooled_cells == 0
    assert mcval.statistic == pytest.approx(ref.statistic, rel=1e-10)
    assert mcval.p_value == pytest.approx(ref.pvalue, rel=1e-8)


def test_goodness_of_fit_pools_small_cells_by_hand():
    assert MIN_EXPECTED == 5.0
    # Cells expecting 2, 1.5 and 3 (< 5) are merged into one bin expecting 6.5 (which stands alone);
    # the cell expecting 5 exactly is not pooled.
    expected = np.array([40.0, 2.0, 30.0, 1.5, 5.0, 3.0, 18.5])
    observed = np.array([35, 6, 33, 4, 2, 1, 19])
    mcval = goodness_of_fit(observed, expected)
    merged_o = np.array([35, 33, 2, 19, 6 + 4 + 1])
    merged_e = np.array([40.0, 30.0, 5.0, 18.5, 6.5])
    ref = sps.chisquare(merged_o, merged_e)
    assert mcval.pooled_cells == 3
    assert mcval.dof == 4
    assert mcval.statistic == pytest.approx(ref.statistic, rel=1e-12)
    assert mcval.p_value == pytest.approx(ref.pvalue, rel=1e-10)


def test_goodness_of_fit_folds_a_too_small_pool_into_the_smallest_bin():
    # Pooled cells expect 1 + 2 = 3 < 5: folded into the smallest regular bin (expecting 7).
    expected = np.array([50.0, 1.0, 7.0, 2.0, 40.0])
    observed = np.array([52, 3, 4, 1, 40])
    mcval = goodness_of_fit(observed, expected)
    ref = sps.chisquare(np.array([52, 4 + 3 + 1, 40]), np.array([50.0, 10.0, 40.0]))
    assert (mcval.pooled_cells, mcval.dof) == (2, 2)
    assert mcval.statistic == pytest.approx(ref.statistic, rel=1e-12)
    assert mcval.p_value == pytest.approx(ref.pvalue, rel=1e-10)


def test_goodness_of_fit_batch_rows_match_scipy():
    rng = np.random.default_rng(7)
    probs = np.full(20, 1 / 20)
    observed = rng.multinomial(2000, probs, size=5)
    batch = goodness_of_fit_batch(observed, probs * 2000)
    for row, stat, p in zip(observed, batch.statistics, batch.p_values):
        ref = sps.chisquare(row, probs * 2000)
        assert stat == pytest.approx(ref.statistic, rel=1e-10)
        assert p == pytest.approx(ref.pvalue, rel=1e-8)
    assert set(batch.dofs) == {19}


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_homogeneity_matches_scipy_contingency(seed):
    rng = np.random.default_rng(seed)
    probs = rng.uniform(0.5, 2.0, 30)
    probs /= probs.sum()
    a = rng.multinomial(10_000, probs)
    b = rng.multinomial(7_000, probs * (1 + 0.05 * (np.arange(30) % 2)) / np.sum(probs * (1 + 0.05 * (np.arange(30) % 2))))
    mcval = homogeneity(a, b)
    stat, p, dof, _ = sps.chi2_contingency(np.stack([a, b]), correction=False)
    assert mcval.dof == dof == 29
    assert mcval.statistic == pytest.approx(stat, rel=1e-9)
    assert mcval.p_value == pytest.approx(p, rel=1e-7)


def test_goodness_of_fit_pool_of_exactly_min_expected_stands_alone():
    expected = np.array([20.0, 2.0, 3.0, 30.0])  # the low cells expect exactly MIN_EXPECTED together
    observed = np.array([22, 4, 4, 25])
    mcval = goodness_of_fit(observed, expected)
    ref = sps.chisquare(np.array([22, 25, 8]), np.array([20.0, 30.0, 5.0]))
    assert (mcval.pooled_cells, mcval.dof) == (2, 2)
    assert mcval.statistic == pytest.approx(ref.statistic, rel=1e-12)


def test_goodness_of_fit_of_two_and_of_too_few_cells():
    mcval = goodness_of_fit(np.array([10, 14]), np.array([12.0, 12.0]))
    ref = sps.chisquare([10, 14], [12.0, 12.0])
    assert mcval.dof == 1
    assert mcval.p_value == pytest.approx(ref.pvalue, rel=1e-10)
    # One regular cell, or every cell too small to test: not judged (p NaN, dof 0), never a p-value that passes.
    for observed, expected in [([7, 0], [7.0, 0.0]), ([1, 0, 1], [1.0, 1.0, 1.0])]:
        res = goodness_of_fit(np.array(observed), np.array(expected))
        assert res.dof == 0 and np.isnan(res.p_value) and np.isnan(res.statistic)
        assert res.not_judged.startswith("fewer than two cells expect 5 samples or more")
        batch = goodness_of_fit_batch(np.array([observed, observed]), np.array(expected))
        assert batch.dofs.dtype.kind == "i" and list(batch.dofs) == [0, 0] and np.isnan(batch.p_values).all()
    # Integer inputs give the same answer as floats.
    a = goodness_of_fit(np.array([35, 6, 33, 4]), np.array([40, 2, 30, 2]))
    b = goodness_of_fit(np.array([35.0, 6.0, 33.0, 4.0]), np.array([40.0, 2.0, 30.0, 2.0]))
    assert (a.statistic, a.dof, a.p_value) == (b.statistic, b.dof, b.p_value)


def test_homogeneity_pools_small_cells_by_hand():
    a = np.array([400, 3, 300, 1, 250, 0])
    b = np.array([380, 2, 330, 1, 260, 4])
    # Cells 1, 3, 5 expect fewer than 5 in a row under the pooled distribution: merged into one column.
    mcval = homogeneity(a, b)
    table = np.array([[400, 300, 250, 3 + 1 + 0], [380, 330, 260, 2 + 1 + 4]])
    stat, p, dof, _ = sps.chi2_contingency(table, correction=False)
    assert (mcval.pooled_cells, mcval.dof) == (3, dof)
    assert mcval.statistic == pytest.approx(stat, rel=1e-10)
    assert mcval.p_value == pytest.approx(p, rel=1e-8)
    assert isinstance(mcval.pooled_cells, int)


def test_homogeneity_without_samples_on_one_side_is_not_judged():
    counts = np.array([50, 80, 20])
    for a, b in [(np.zeros(3, int), counts), (counts, np.zeros(3, int)), (np.zeros(3, int), np.zeros(3, int))]:
        res = homogeneity(a, b)
        assert res.dof == 0 and np.isnan(res.p_value) and res.not_judged.startswith("an empty histogram")


# --- Sidak ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("alpha, n", [(0.01, 1), (0.01, 3), (0.05, 768), (0.3, 10**6), (0.01, 2)])
def test_sidak_level_is_its_definition(alpha, n):
    assert sidak_level(alpha, n) == pytest.approx(definition_sidak(alpha, n), rel=1e-12)
    # The family-wise rate of n independent tests at that level is alpha.
    assert 1 - (1 - sidak_level(alpha, n)) ** n == pytest.approx(alpha, rel=1e-9)


def test_compare_splits_alpha_over_scales_then_pixels_and_channels():
    rng = np.random.default_rng(0)
    h, w, k = 16, 24, 4
    a = 0.5 + 0.01 * rng.standard_normal((k, h, w, 3))
    b = 0.5 + 0.01 * rng.standard_normal((k, h, w, 3))
    result = compare_batches(a, b, tile=8)
    per_scale = definition_sidak(SIGNIFICANCE, 3)
    counts = {"pixel": h * w * 3, "tile": (h // 8) * (w // 8) * 3, "image": 3}
    assert [s.scale for s in result.scales] == ["pixel", "tile", "image"]
    for s in result.scales:
        assert s.tests == counts[s.scale], s.scale
        # Independent channels (their estimated correlation is near 0) and no element without noise: Sidak,
        # but for the rounding floor, which shrinks the image-mean tests by 4e-4 and so raises their level.
        assert s.level == pytest.approx(definition_sidak(per_scale, counts[s.scale]), rel=5e-3), s.scale
    # Same levels with another alpha: they follow it.
    result = compare_batches(a, b, alpha=0.05, tile=8)
    assert result.scales[2].level == pytest.approx(definition_sidak(definition_sidak(0.05, 3), 3), rel=5e-3)


# --- metrics and efficiency ------------------------------------------------------------------------

def test_psnr_is_its_definition():
    rng = np.random.default_rng(3)
    reference = rng.uniform(0.0, 2.0, (16, 16, 3))
    test = reference + rng.normal(0.0, 0.05, reference.shape)
    m = image_metrics(test, reference)
    mse = np.mean((test - reference) ** 2)
    assert m["mse"] == pytest.approx(mse, rel=1e-12)
    assert m["rmse"] == pytest.approx(np.sqrt(mse), rel=1e-12)
    assert m["psnr"] == pytest.approx(10 * np.log10(np.max(np.abs(reference)) ** 2 / mse), rel=1e-12)
    assert m["mean_ratio"] == pytest.approx(np.mean(test) / np.mean(reference), rel=1e-12)
    assert image_metrics(reference, reference)["psnr"] == float("inf")


def _curve(name, error_constant, seconds_per_spp):
    """relMSE = error_constant / spp and seconds = seconds_per_spp * spp: efficiency 1/(c * s)."""
    steps = [Step(s, [seconds_per_spp * s] * 3, [error_constant / s] * 3, [0.1] * 3) for s in (4, 8, 16, 32, 64)]
    return Curve(name, "render only", steps, 0.1)


def test_efficiency_ratio_has_its_known_answer():
    mcval = _curve("mcval", 0.5, 0.01)       # efficiency 1 / (0.5 * 0.01) = 200
    other = _curve("mitsuba", 2.0, 0.02)    # efficiency 1 / (2 * 0.02) = 25
    assert mcval.efficiency() == pytest.approx(200.0)
    assert other.efficiency() == pytest.approx(25.0)
    bench = CaseBench(None, {"mcval": mcval, "mitsuba": other}, np.zeros(3))
    assert bench.efficiency_ratio() == pytest.approx(8.0)  # mcval is 8x as efficient
    assert bench.efficiency_ratio("mitsuba", "mcval") == pytest.approx(1 / 8.0)
    assert np.isnan(CaseBench(None, {"mcval": mcval}, np.zeros(3)).efficiency_ratio())


# --- regression report ------------------------------------------------------------------------------

def _entry(scene="cornell", passed=True, mean=(0.5, 0.5, 0.5), se=(1e-3, 1e-3, 1e-3), seconds=1.0, relmse=1e-3,
           error=None):
    e = {"integrator": "simple", "scene": scene, "engine": "mcval", "pass": passed, "seconds": {"mcval": {"total": seconds}},
         "metrics": {"relmse": relmse}}
    if mean is not None:
        e.update(image_mean=list(mean), image_mean_se=list(se))
    if error:
        e["error"] = error
    return e


def test_regression_report_flags_each_change_by_its_rule():
    from harness.images.regression import MEAN_SIGMAS, TIME_FACTOR, TIME_FLOOR, compare_runs

    assert (MEAN_SIGMAS, TIME_FACTOR, TIME_FLOOR) == (4.0, 1.5, 0.25)
    base = {"images": [_entry(relmse=2e-3), _entry("plane", passed=False)]}

    def flags(*current):
        return [(r["scene"], r["flags"]) for r in compare_runs(list(current), base)]

    assert flags(_entry(), _entry("plane", passed=False)) == [("cornell", []), ("plane", [])]
    (entry,) = compare_runs([_entry(relmse=5e-4)], base)
    assert entry == {"integrator": "simple", "scene": "cornell", "flags": [], "relmse_before": 2e-3,
                     "relmse_now": 5e-4}
    (entry,) = compare_runs([_entry("new")], base)
    assert entry["flags"] == ["new case"] and entry["relmse_before"] is None and entry["relmse_now"] == 1e-3
    assert flags(_entry(passed=False)) == [("cornell", ["verdict PASS -> FAIL"])]
    assert flags(_entry("plane")) == [("plane", ["verdict FAIL -> PASS"])]
    # A failed render: its error, and nothing measured.
    assert flags(_entry(passed=False, mean=None, error="timed out", seconds=50.0)) == \
        [("cornell", ["verdict PASS -> FAIL", "render failed: timed out"])]
    # The same failure again is no news; the entries after a failed render are still compared.
    failed = {"images": [_entry(passed=False, mean=None, error="timed out", relmse=2e-3), _entry("plane")]}
    again = compare_runs([_entry(passed=False, mean=None, error="timed out"), _entry("plane", seconds=9.0)], failed)
    assert [r["flags"] for r in again] == [[], ["time 1.00s -> 9.00s"]]
    assert again[0]["relmse_before"] == 2e-3
    # Times: beyond a factor 1.5 and 0.25 s either way.
    slow = {"images": [_entry(seconds=2.0), _entry("plane", seconds=0.5)]}
    assert [r["flags"] for r in compare_runs([_entry(seconds=2.5), _entry("plane", seconds=0.9)], slow)] == \
        [[], ["time 0.50s -> 0.90s"]]
    assert [r["flags"] for r in compare_runs([_entry(seconds=1.2), _entry("plane", seconds=0.74)], slow)] == \
        [["time 2.00s -> 1.20s"], []]
    assert flags(_entry(seconds=1.6)) == [("cornell", ["time 1.00s -> 1.60s"])]
    assert flags(_entry(seconds=0.6)) == [("cornell", ["time 1.00s -> 0.60s"])]
    assert flags(_entry(seconds=1.45), _entry("plane", passed=False, seconds=0.7)) == [("cornell", []), ("plane", [])]
    small = {"images": [_entry(seconds=0.07)]}
    assert compare_runs([_entry(seconds=0.3)], small)[0]["flags"] == []  # 4x, but only 0.23 s
    assert compare_runs([_entry(seconds=0.33)], small)[0]["flags"] == ["time 0.07s -> 0.33s"]
    # The mean: its flag names the standard errors and the relative change.
    moved = compare_runs([_entry(mean=(0.5, 0.5, 0.51))], base)[0]["flags"]
    assert moved == [f"image mean moved {0.01 / np.hypot(1e-3, 1e-3):.1f} standard errors (+0.67%)"]
    # NaN and Inf written as strings in results.json are read as numbers.
    assert compare_runs([_entry(mean=("nan", 0.5, 0.5))], base)[0]["flags"] == []
    stringy = {"images": [_entry(mean=("nan", 0.5, 0.5), se=("nan", 1e-3, 1e-3))]}
    assert compare_runs([_entry(mean=(0.5, 0.5, 0.6), se=(1e-3, 1e-3, "inf"))], stringy)[0]["flags"] == []
    assert compare_runs([_entry(mean=(0.5, 0.6, 0.5))], stringy)[0]["flags"]
    # A baseline with no standard error (0): any change of the mean counts.
    exact = {"images": [_entry(se=(0.0, 0.0, 0.0))]}
    assert compare_runs([_entry(mean=(0.5, 0.5, 0.5), se=(0.0, 0.0, 0.0))], exact)[0]["flags"] == []
    assert compare_runs([_entry(mean=(0.5, 0.5, 0.5001), se=(0.0, 0.0, 0.0))], exact)[0]["flags"]


def test_regression_baseline_loading(tmp_path):
    import json

    from harness.images.regression import load_baseline

    assert load_baseline(tmp_path / "missing.json") is None
    (tmp_path / "bad.json").write_text("{not json")
    assert load_baseline(tmp_path / "bad.json") is None
    (tmp_path / "empty.json").write_text(json.dumps({"images": []}))
    assert load_baseline(tmp_path / "empty.json") is None
    (tmp_path / "ok.json").write_text(json.dumps({"images": [_entry()]}))
    assert load_baseline(tmp_path / "ok.json")["images"][0]["scene"] == "cornell"


# --- the other metrics ------------------------------------------------------------------------------

def test_metrics_follow_their_definitions():
    from skimage.metrics import structural_similarity

    from harness.comparison.metrics import RELMSE_EPSILON, _tonemapped

    rng = np.random.default_rng(4)
    reference = rng.uniform(0.0, 2.0, (16, 16, 3))
    reference[0, 0] = 0.0
    test = reference + rng.normal(0.0, 0.05, reference.shape)
    test[0, 0] = 0.0  # 0 against 0: a SMAPE term of 0
    m = image_metrics(test, reference)
    diff = test - reference
    assert RELMSE_EPSILON == 1e-2
    assert m["relmse"] == pytest.approx(np.mean(diff**2 / (reference**2 + 1e-2)), rel=1e-12)
    denominator = np.abs(test) + np.abs(reference)
    terms = np.where(denominator > 0, 2 * np.abs(diff) / np.where(denominator > 0, denominator, 1), 0.0)
    assert m["smape"] == pytest.approx(np.mean(terms), rel=1e-12)
    data_range = reference.max() - reference.min()
    assert m["ssim"] == pytest.approx(structural_similarity(test, reference, channel_axis=-1, data_range=data_range),
                                      rel=1e-12)
    assert 0 < m["flip_mean"] <= m["flip_p95"] < 1
    assert m["ciede2000_mean"] > 0
    identical = image_metrics(reference, reference)
    assert identical["ssim"] == pytest.approx(1.0) and identical["flip_mean"] == 0.0
    assert identical["ciede2000_mean"] == pytest.approx(0.0, abs=1e-9) and identical["smape"] == 0.0
    # Tone mapping: radiance clipped to [0, 1], normals mapped from [-1, 1].
    x = np.array([-2.0, -1.0, 0.0, 0.5, 1.0, 3.0])
    np.testing.assert_allclose(_tonemapped(x, False), [0, 0, 0, 0.5, 1, 1])
    np.testing.assert_allclose(_tonemapped(x, True), [0, 0, 0.5, 0.75, 1, 1])
    # A black reference: PSNR against a peak of 1, a mean ratio that is NaN.
    black = np.zeros((16, 16, 3))
    m = image_metrics(black + 0.1, black)
    assert m["psnr"] == pytest.approx(10 * np.log10(1 / 0.01), rel=1e-12)
    assert np.isnan(m["mean_ratio"])
    # Normals: the signed metrics see (x + 1) / 2; a constant image has SSIM's data range of 1.
    normals = np.clip(reference - 1.0, -1, 1)
    m = image_metrics(normals, normals, signed=True)
    assert m["ciede2000_mean"] == pytest.approx(0.0, abs=1e-9) and m["flip_mean"] == 0.0
    flat = np.full((16, 16, 3), 0.5)
    assert image_metrics(flat + 0.01, flat)["ssim"] == pytest.approx(
        structural_similarity(flat + 0.01, flat, channel_axis=-1, data_range=1.0), rel=1e-12)


def test_flip_ssim_and_ciede_take_their_documented_settings():
    import colour
    import flip_evaluator as flip
    from skimage.metrics import structural_similarity

    from harness.comparison.metrics import flip_map

    rng = np.random.default_rng(6)
    reference = rng.uniform(0.5, 3.0, (16, 16, 3))
    test = reference * rng.uniform(0.8, 1.2, reference.shape)
    test[0, 0] = -0.5  # clipped to 0 for HDR-FLIP
    m = image_metrics(test, reference)
    peak = reference.max()
    error, mean, _ = flip.evaluate((reference / peak).astype(np.float32),
                                   (np.clip(test, 0, None) / peak).astype(np.float32), "HDR", inputsRGB=True,
                                   applyMagma=False)
    error = np.asarray(error)[..., 0]
    assert m["flip_mean"] == pytest.approx(float(mean), rel=1e-6)
    assert m["flip_p95"] == pytest.approx(float(np.percentile(error, 95)), rel=1e-6)
    assert m["ssim"] == pytest.approx(structural_similarity(test, reference, channel_axis=-1,
                                                            data_range=reference.max() - reference.min()), rel=1e-12)
    lab = [colour.XYZ_to_Lab(colour.sRGB_to_XYZ(np.clip(x, 0, 1), apply_cctf_decoding=False)) for x in (test, reference)]
    assert m["ciede2000_mean"] == pytest.approx(float(np.mean(colour.delta_E(lab[0], lab[1], method="CIE 2000"))),
                                                rel=1e-9)
    # Normals: LDR-FLIP on (x + 1) / 2, no sRGB decoding.
    normals_ref = np.clip(reference - 1.5, -1, 1)
    normals = np.clip(normals_ref + rng.normal(0, 0.1, reference.shape), -1, 1)
    m = image_metrics(normals, normals_ref, signed=True)
    error, mean, _ = flip.evaluate(((normals_ref + 1) / 2).astype(np.float32), ((normals + 1) / 2).astype(np.float32),
                                   "LDR", inputsRGB=False, applyMagma=False)
    assert m["flip_mean"] == pytest.approx(float(mean), rel=1e-6)
    lab = [colour.XYZ_to_Lab(colour.sRGB_to_XYZ((x + 1) / 2, apply_cctf_decoding=False)) for x in (normals, normals_ref)]
    assert m["ciede2000_mean"] == pytest.approx(float(np.mean(colour.delta_E(lab[0], lab[1], method="CIE 2000"))),
                                                rel=1e-9)
    # A black reference: a NaN map of the image's size.
    nan_map, nan_mean = flip_map(test, np.zeros_like(test))
    assert nan_map.shape == (16, 16) and np.isnan(nan_map).all() and np.isnan(nan_mean)
