"""The chi-square tests are calibrated (false alarms at the stated rate) and have power."""
import numpy as np
import pytest
from scipy import stats as sps

from harness.statistics.chi2 import goodness_of_fit, homogeneity
from harness.statistics.cubature import integrate_cells
from harness.statistics.constants import sidak_level

RUNS = 300
LEVEL = 0.05


def _false_alarm_interval():
    return sps.binom.interval(0.999, RUNS, LEVEL)


def _uniform_counts(rng, n, cells, tilt=0.0):
    """Counts of n draws over `cells` cells, uniform or tilted linearly by `tilt`."""
    p = 1.0 + tilt * np.linspace(-1, 1, cells)
    return rng.multinomial(n, p / p.sum()).astype(float)


def test_goodness_of_fit_false_alarm_rate_matches_level():
    rng = np.random.default_rng(7)
    cells = 225
    expected = np.full(cells, 20_000 / cells)
    p_values = np.array([goodness_of_fit(_uniform_counts(rng, 20_000, cells), expected).p_value
                         for _ in range(RUNS)])
    lo, hi = _false_alarm_interval()
    assert lo <= np.sum(p_values < LEVEL) <= hi
    assert sps.kstest(p_values, "uniform").pvalue > 1e-3


def test_goodness_of_fit_rejects_a_four_percent_tilt():
    rng = np.random.default_rng(8)
    cells = 225
    expected = np.full(cells, 1e6 / cells)
    for _ in range(5):
        assert goodness_of_fit(_uniform_counts(rng, 1_000_000, cells, tilt=0.04), expected).p_value < 1e-4


def test_goodness_of_fit_rejects_wrong_normalisation():
    observed = np.full(100, 1000.0)
    assert goodness_of_fit(observed, observed * 1.05).p_value < 1e-6


def test_pooling_keeps_sparse_tails_valid():
    rng = np.random.default_rng(9)
    p = np.exp(-np.linspace(0, 12, 200))
    p /= p.sum()
    p_values = [goodness_of_fit(rng.multinomial(5000, p), 5000 * p).p_value for _ in range(RUNS)]
    lo, hi = _false_alarm_interval()
    assert lo <= np.sum(np.array(p_values) < LEVEL) <= hi
    assert goodness_of_fit(rng.multinomial(5000, p), 5000 * p).pooled_cells > 50


def test_homogeneity_false_alarm_rate_and_power():
    rng = np.random.default_rng(10)
    p_values = np.array([homogeneity(_uniform_counts(rng, 20_000, 225), _uniform_counts(rng, 20_000, 225)).p_value
                         for _ in range(RUNS)])
    lo, hi = _false_alarm_interval()
    assert lo <= np.sum(p_values < LEVEL) <= hi
    assert homogeneity(_uniform_counts(rng, 10**6, 225), _uniform_counts(rng, 10**6, 225, tilt=0.03)).p_value < 1e-4


def test_sidak_level():
    assert sidak_level(0.01, 1) == pytest.approx(0.01)
    n = 21
    assert 1 - (1 - sidak_level(0.01, n)) ** n == pytest.approx(0.01)


def test_cell_integrals_of_smooth_and_peaked_densities():
    res = integrate_cells(lambda s, t: 6 * s * t * t, 15)
    edges = np.arange(16) / 15
    exact = np.outer(np.diff(edges**2), np.diff(edges**3))
    assert np.allclose(res.values, exact, rtol=1e-9, atol=1e-14)
    # A spike of width 1e-4 at the edge of one cell: a fixed rule misses it, the adaptive one does not.
    width = 1e-4
    res = integrate_cells(lambda s, t: np.exp(-(1 - s) / width) / width, 51)
    assert res.values.sum() == pytest.approx(1.0, abs=1e-6)


def test_batch_tests_agree_with_single_ones_and_with_scipy():
    from harness.statistics.chi2 import goodness_of_fit_batch, homogeneity_batch
    rng = np.random.default_rng(11)
    for _ in range(100):
        k = int(rng.integers(2, 40))
        p = rng.dirichlet(np.full(k, 0.3))  # many sparse cells: pooling and empty columns
        a = rng.multinomial(int(rng.integers(5, 2000)), p, size=3).astype(float)
        b = rng.multinomial(int(rng.integers(5, 2000)), p, size=3).astype(float)
        batch = homogeneity_batch(a, b)
        for i in range(3):
            share = a[i].sum() / (a[i].sum() + b[i].sum())
            low = np.minimum(share, 1 - share) * (a[i] + b[i]) < 5
            table = np.stack([a[i][~low], b[i][~low]])
            if low.any():
                table = np.concatenate([table, [[a[i][low].sum()], [b[i][low].sum()]]], axis=1)
            table = table[:, table.sum(axis=0) > 0]
            if table.shape[1] < 2:  # no test: not judged, never a p-value that passes
                assert np.isnan(batch.p_values[i]) and batch.dofs[i] == 0
                assert homogeneity(a[i], b[i]).not_judged
                continue
            ref = sps.chi2_contingency(table, correction=False)
            assert batch.statistics[i] == pytest.approx(ref.statistic, rel=1e-9, abs=1e-12)
            assert batch.dofs[i] == ref.dof and batch.p_values[i] == pytest.approx(ref.pvalue, rel=1e-9)
            assert homogeneity(a[i], b[i]).p_value == pytest.approx(batch.p_values[i], rel=1e-9)
        expected = 500 * p
        gof = goodness_of_fit_batch(a, expected)
        for i in range(3):
            single = goodness_of_fit(a[i], expected)
            assert gof.statistics[i] == pytest.approx(single.statistic, rel=1e-12, nan_ok=True)
            assert gof.dofs[i] == single.dof
            assert gof.p_values[i] == pytest.approx(single.p_value, rel=1e-9, nan_ok=True)


def test_cell_integrals_on_uneven_edges_and_thin_spikes():
    s_edges = np.array([0.0, 0.1, 0.15, 0.6, 0.999, 1.0])
    t_edges = np.array([0.0, 0.3, 1.0])
    res = integrate_cells(lambda s, t: 6 * s * t * t, s_edges, t_edges)
    assert res.values.shape == (5, 2)
    assert np.allclose(res.values, np.outer(np.diff(s_edges**2), np.diff(t_edges**3)), rtol=1e-9, atol=1e-14)
    # Beckmann at alpha 0.001 in cos theta: all of the lowest equal-probability cell's mass (1/51) lies within
    # 1e-5 of its upper edge, between the Gauss nodes of every coarse estimate; the corner check finds it.
    a2, res_ = 1e-6, 51
    top = 1 / np.sqrt(1 - a2 * np.log(1 / res_))

    def density(s, t):
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            return np.where(s > 0, 2 / (a2 * s**3) * np.exp(-(1 / s**2 - 1) / a2), 0.0)
    res = integrate_cells(density, np.array([0.0, top, 1.0]), np.array([0.0, 1.0]))
    assert res.values.ravel() == pytest.approx([1 / res_, 1 - 1 / res_], rel=1e-6)


# --- Counts a test cannot judge: never a p-value that passes ------------------------------------------------

@pytest.mark.parametrize("integral", [6e-6, 1e-5, 1e-3])
def test_a_pdf_integrating_far_below_one_is_not_judged(integral):
    # Expected counts N * integral / cells: every cell below 5, pooled into a single bin, which is no test.
    observed = np.random.default_rng(3).multinomial(10**6, np.full(2601, 1 / 2601))
    res = goodness_of_fit(observed, np.full(2601, 10**6 * integral / 2601))
    assert res.not_judged and np.isnan(res.p_value) and "1000000 observed" in res.not_judged


def test_counts_that_are_not_finite_or_negative_are_not_judged():
    good = np.full(10, 100.0)
    for observed, expected in [(good, np.where(np.arange(10) == 3, np.inf, 100.0)), (good * np.nan, good),
                               (good, -good)]:
        assert goodness_of_fit(observed, expected).not_judged
        assert homogeneity(observed, expected).not_judged


def test_homogeneity_with_every_count_in_one_bin_is_not_judged():
    a, b = np.array([0, 500, 0]), np.array([0, 700, 0])
    assert homogeneity(a, b).not_judged == "every count of both histograms in one bin"
