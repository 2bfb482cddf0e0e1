"""Equal-probability cells are right and keep the chi-square valid; the power figures are what they claim."""
import numpy as np
import pytest

from harness.warps import checks as wc
from harness.warps.check_result import CheckResult
from harness.statistics.chi2 import goodness_of_fit, homogeneity
from harness.warps.domains import get_domain
from harness.statistics.constants import FLOAT32_QUANTUM, HISTOGRAM_RES
from harness.warps.bins import equal_probability_bins, uniform_bins
from harness.warps.power import (attach_power, lower_half, mass_moved_defect, pdf_half_defect, simulated_powers)
from harness.warps.suite import run_matrix, select
from harness.warps.evaluate import check_warp
from tests.helpers.wrong_warps import beckmann_pdf, beckmann_sample, cosine_pdf, disk_pdf, disk_sample, tent_pdf

R = HISTOGRAM_RES
K = np.arange(1, R)
N = 1_000_000
#: About the matrix's per-test level (Sidak over 21 tests at 0.01).
LEVEL = 0.00048


def _bins(domain, pdf, quantum=0.0):
    return equal_probability_bins(wc.parameter_density(get_domain(domain), pdf), R, N, quantum)


@pytest.mark.parametrize("alpha", [0.3, 0.01, 0.001])
def test_beckmann_edges_are_the_quantiles_of_its_cos_theta_marginal(alpha):
    # P(cos theta <= s) = exp(-(1/s^2 - 1) / alpha^2): the k/R quantile is 1 / sqrt(1 - alpha^2 ln(k/R)).
    bins = _bins("hemisphere", beckmann_pdf(alpha))
    exact = 1 / np.sqrt(1 - alpha**2 * np.log(K / R))
    assert bins.kind == "equal-probability" and bins.shape == (R, R)
    assert np.max(np.abs(bins.s_edges[1:-1] - exact)) < 1e-6
    assert np.max(np.abs((bins.s_edges[1:-1] - exact) / (1 - exact))) < 1e-4  # also near the pole
    assert np.array_equal(bins.t_edges, np.arange(R + 1) / R)  # isotropic: uniform in t, exactly


def test_cosine_and_tent_edges_match_closed_forms():
    cosine = _bins("hemisphere", cosine_pdf)  # CDF s^2
    assert np.max(np.abs(cosine.s_edges[1:-1] - np.sqrt(K / R))) < 1e-6
    tent = _bins("tent", tent_pdf)  # CDF 2 s^2 below 1/2, 1 - 2 (1 - s)^2 above, in both coordinates
    q = K / R
    exact = np.where(q < 0.5, np.sqrt(q / 2), 1 - np.sqrt((1 - q) / 2))
    assert np.max(np.abs(tent.s_edges[1:-1] - exact)) < 1e-6
    assert np.max(np.abs(tent.t_edges[1:-1] - exact)) < 1e-6


def test_every_cell_of_a_separable_pdf_expects_the_same_count():
    dom = get_domain("hemisphere")
    for pdf in (beckmann_pdf(0.01), beckmann_pdf(0.001), cosine_pdf):
        bins = _bins("hemisphere", pdf)
        cells = wc.expected_probabilities(dom, pdf, bins).values
        assert cells.sum() == pytest.approx(1.0, abs=1e-6)
        assert np.allclose(cells * R * R, 1.0, rtol=1e-4)


def test_a_pdf_off_by_a_constant_has_the_same_cells_and_still_fails():
    right, wrong = _bins("disk", disk_pdf), _bins("disk", lambda p: np.pi * disk_pdf(p))
    assert np.array_equal(right.s_edges, wrong.s_edges) and np.array_equal(right.t_edges, wrong.t_edges)
    r = check_warp(disk_sample, lambda p: np.pi * disk_pdf(p), "disk", samples=200_000)
    assert r.checks["normalisation"].passed is False and r.checks["chi2"].passed is False


def test_pdf_zero_over_a_range_and_pdf_without_mass():
    def half_pdf(p):  # uniform on the upper half of the square
        return np.where(p[:, 0] >= 0.5, 2.0, 0.0)
    bins = _bins("square", half_pdf)
    assert bins.s_edges[1] == pytest.approx(0.5 + 0.5 / R, abs=1e-6)
    r = check_warp(lambda u: np.stack([0.5 + 0.5 * u[:, 0], u[:, 1]], -1), half_pdf, "square", samples=200_000)
    assert r.checks["chi2"].passed, r.checks["chi2"].summary
    for bad in (lambda p: np.zeros(len(p)), lambda p: np.full(len(p), np.nan), lambda p: -np.ones(len(p))):
        assert _bins("square", bad).kind == "uniform"


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("alpha", [0.01, 0.001])
def test_correct_beckmann_passes_with_equal_probability_cells(alpha, seed):
    r = check_warp(beckmann_sample(alpha), beckmann_pdf(alpha), "hemisphere", seed=seed)
    assert r.passed, {k: c.summary for k, c in r.checks.items()}
    assert r.checks["chi2"].details["cells"] == [R, R]


@pytest.mark.slow
def test_float32_samples_get_cells_their_rounding_cannot_bias():
    assert _bins("hemisphere", beckmann_pdf(0.3), FLOAT32_QUANTUM).shape == (R, R)
    assert _bins("hemisphere", beckmann_pdf(0.01), FLOAT32_QUANTUM).shape == (2, R)
    for seed in range(3):
        r = check_warp(lambda u: beckmann_sample(0.01)(u).astype(np.float32), beckmann_pdf(0.01), "hemisphere",
                       seed=seed)
        assert r.checks["chi2"].passed and r.checks["chi2"].details["cells"] == [2, R]
        assert "float32" in r.checks["chi2"].details["cells_limited_by"]


def test_directions_at_the_pole_are_spread_over_the_azimuths():
    points = np.array([[0.0, 0.0, 1.0]] * 51 + [[1.0, 0.0, 0.0]])
    h = wc.histogram(get_domain("hemisphere"), points, uniform_bins(R))
    assert np.allclose(h[-1], 1.0) and h[0, 0] == 1 and h.sum() == 52


@pytest.mark.slow
def test_beckmann_twins_are_caught_at_alpha_001():
    # alpha where alpha^2 belongs: a lobe ten times too wide.
    assert check_warp(beckmann_sample(0.01, False), beckmann_pdf(0.01), "hemisphere").checks["chi2"].passed is False
    # A roughness 2% too high: all the mass stays in the top row of the uniform grid, invisible there.
    dom, wrong = get_domain("hemisphere"), beckmann_sample(0.0102)
    points = wrong(np.random.default_rng(0).random((N, 2)))
    grid = uniform_bins(R)
    expected = wc.expected_probabilities(dom, beckmann_pdf(0.01), grid).values
    old = wc.chi2_check(wc.histogram(dom, points, grid), expected, 0)
    assert old.p_value > 0.01
    assert check_warp(wrong, beckmann_pdf(0.01), "hemisphere").checks["chi2"].p_value < 1e-20
    as_float32 = check_warp(lambda u: wrong(u).astype(np.float32), beckmann_pdf(0.01), "hemisphere")
    assert as_float32.checks["chi2"].p_value < 1e-20


def test_defects_keep_the_total_and_split_the_mass_in_halves():
    p = np.full((R, R), 1 / R**2)
    half = lower_half(p)
    assert half[: R // 2].all() and not half[R // 2 + 1:].any()
    assert p[half].sum() == pytest.approx(0.5, abs=1 / R**2)
    assert pdf_half_defect(p, 0.01).sum() == pytest.approx(1.0)
    moved = mass_moved_defect(p, 0.01)
    assert moved.sum() == pytest.approx(1.0) and p[half].sum() - moved[half].sum() == pytest.approx(0.01)


@pytest.fixture(scope="module")
def uniform_powers():
    return simulated_powers(np.full((R, R), 1 / R**2), N, LEVEL, reference=True)


def _rate(detect, runs=30):
    return np.mean([detect(np.random.default_rng(1000 + i)) for i in range(runs)])


def test_the_reported_defect_is_detected_and_a_quarter_of_it_is_not(uniform_powers):
    p = np.full((R, R), 1 / R**2)
    eps, delta = (f.detects_90 for f in uniform_powers["chi2"])
    delta_mi = uniform_powers["samples_vs_mitsuba"][0].detects_90
    assert 0.005 < eps < 0.05 and 0.0025 < delta < 0.025 and 0.0025 < delta_mi < 0.05

    def pdf_wrong(x):
        return lambda rng: goodness_of_fit(rng.multinomial(N, p.ravel()),
                                           N * pdf_half_defect(p, x).ravel()).p_value < LEVEL

    def sampler_wrong(x):
        return lambda rng: goodness_of_fit(rng.multinomial(N, mass_moved_defect(p, x).ravel()),
                                           N * p.ravel()).p_value < LEVEL

    def against_reference(x):
        return lambda rng: homogeneity(rng.multinomial(N, mass_moved_defect(p, x).ravel()),
                                       rng.multinomial(N, p.ravel())).p_value < LEVEL
    for make, x in ((pdf_wrong, eps), (sampler_wrong, delta), (against_reference, delta_mi)):
        assert _rate(make(x)) >= 0.8
        assert _rate(make(x / 4)) <= 0.3


def test_power_at_alpha_001_is_within_2x_of_alpha_03(mcval, mitsuba, tmp_path):
    results, level = run_matrix(mcval, mitsuba, select(["beckmann:0.01", "beckmann:0.3"]),
                                power_cache=tmp_path / "power.json")
    eps = {r.params["alpha"]: r.checks["chi2"].details["power"][0]["detects_90"] for r in results}
    assert eps[0.01] <= 2 * eps[0.3]
    assert all(r.checks["samples_vs_mitsuba"].details["power"][0]["detects_90"] for r in results)
    assert results[0].checks["normalisation"].details["power"][0]["detects_90"] == 1e-3


class _Fake:
    def __init__(self, p):
        self.expected, self.reference_observed = N * p, None
        self.checks = {"chi2": CheckResult(True, 0.5, "p = 0.5", p_value=0.5),
                       "normalisation": CheckResult(True, 1.0, "integral = 1")}


def test_power_is_cached_by_warp_and_cells(tmp_path, monkeypatch):
    cache = tmp_path / "power.json"
    first = _Fake(np.full((9, 9), 1 / 81))
    attach_power([first], ["square"], N, LEVEL, cache)
    assert cache.exists() and first.checks["chi2"].details["power"][0]["replications"] == 200

    def fail(*args, **kwargs):
        raise AssertionError("simulated again")
    monkeypatch.setattr("harness.warps.power.simulated_powers", fail)
    again = _Fake(np.full((9, 9), 1 / 81))
    attach_power([again], ["square"], N, LEVEL, cache)
    assert again.checks["chi2"].details["power"] == first.checks["chi2"].details["power"]
    tilted = np.linspace(1, 2, 81).reshape(9, 9)
    with pytest.raises(AssertionError, match="simulated again"):
        attach_power([_Fake(tilted / tilted.sum())], ["square"], N, LEVEL, cache)
