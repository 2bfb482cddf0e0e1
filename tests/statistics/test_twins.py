"""Known-wrong twins at the edge of detection, through the real checks.

Each wrong twin is only just wrong (a pdf 1 % off, a normalisation 0.5 % off, a Beckmann alpha 1 %
off, an image mean moved by 5 standard errors, a bias of exactly the reported detectable size) and
must be caught; its correct twin (0.05 % off, 1 standard error, ...) must pass, over several seeds.
"""
import numpy as np
import pytest
from scipy import stats as sps
from scipy.optimize import brentq

from harness.bench.ladder import Curve, Step
from harness.bench.run import CaseBench
from harness.comparison.compare import compare_batches
from harness.warps.domains import get_domain
from harness.statistics.constants import IMAGE_POWER_TARGET
from harness.images.regression import MEAN_SIGMAS, compare_runs
from harness.warps.checks import expected_probabilities, normalisation_check
from harness.warps.pdf_agreement import pdf_agreement_check
from harness.warps.evaluate import check_warp

TWO_PI = 2 * np.pi
ONE_MINUS_EPS = np.nextafter(1.0, 0.0)


def _direction(z, phi):
    r = np.sqrt(np.clip(1 - z * z, 0, None))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def cosine_sample(u):
    return _direction(np.sqrt(1 - np.minimum(u[:, 0], ONE_MINUS_EPS)), TWO_PI * u[:, 1])


def cosine_pdf(v):
    return np.where(v[:, 2] > 0, v[:, 2] / np.pi, 0.0)


def float32_cosine_pdf(v):
    """A float32 cosine-hemisphere pdf, as Mitsuba computes it."""
    z = v[:, 2].astype(np.float32)
    return np.where(z > 0, z * np.float32(1 / np.pi), np.float32(0)).astype(np.float64)


def hemisphere_pdf(v):
    return np.where(v[:, 2] >= 0, 1 / TWO_PI, 0.0)


def disk_pdf(p):
    return np.where(np.sum(p * p, axis=1) <= 1, 1 / np.pi, 0.0)


def beckmann_sample(alpha):
    """Exact inversion of the Beckmann distribution of normals (pdf D(m) cos(theta_m)):
    tan^2(theta) = -alpha^2 log(1 - u), phi = 2 pi u'."""
    def sample(u):
        tan2 = -alpha * alpha * np.log1p(-np.minimum(u[:, 1], ONE_MINUS_EPS))
        return _direction(1 / np.sqrt(1 + tan2), TWO_PI * u[:, 0])
    return sample


def beckmann_pdf(alpha):
    def pdf(v):
        z = v[:, 2]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            tan2 = (v[:, 0] ** 2 + v[:, 1] ** 2) / (z * z)
            d = np.exp(-tan2 / alpha**2) / (np.pi * alpha**2 * z**3)
        return np.where(z > 0, np.nan_to_num(d), 0.0)
    return pdf


def scaled(pdf, factor):
    return lambda v: factor * pdf(v)


def _probe_points(seed, n=50_000):
    return cosine_sample(np.random.default_rng(seed).random((n, 2)))


# --- pdf against the reference implementation -------------------------------------------------------

@pytest.mark.parametrize("seed", [0, 1, 2])
def test_pdf_one_percent_off_the_reference_fails_and_0_05_percent_passes(seed):
    points = _probe_points(seed)
    assert pdf_agreement_check(points, scaled(cosine_pdf, 1.01), float32_cosine_pdf).passed is False
    assert pdf_agreement_check(points, scaled(cosine_pdf, 0.99), float32_cosine_pdf).passed is False
    assert pdf_agreement_check(points, scaled(cosine_pdf, 1.0005), float32_cosine_pdf).passed is True
    assert pdf_agreement_check(points, cosine_pdf, float32_cosine_pdf).passed is True


def test_pdf_one_percent_off_mitsuba_fails_and_0_05_percent_passes():
    from harness.engines.mitsuba import load_mitsuba
    from harness.warps.adapters import masked_to_domain

    mi = load_mitsuba()
    reference = masked_to_domain(mi.warp.square_to_cosine_hemisphere_pdf, "hemisphere")
    for seed in (0, 1):
        points = _probe_points(seed)
        assert pdf_agreement_check(points, scaled(cosine_pdf, 1.01), reference).passed is False
        assert pdf_agreement_check(points, scaled(cosine_pdf, 1.0005), reference).passed is True


# --- normalisation ----------------------------------------------------------------------------------

@pytest.mark.parametrize("pdf, domain", [(cosine_pdf, "hemisphere"), (hemisphere_pdf, "hemisphere"),
                                         (disk_pdf, "disk")], ids=["cosine", "hemisphere", "disk"])
def test_normalisation_half_a_percent_off_fails_and_0_05_percent_passes(pdf, domain):
    dom = get_domain(domain)
    for factor, ok in [(1.005, False), (0.995, False), (1.0005, True), (0.9995, True), (1.0, True)]:
        cells = expected_probabilities(dom, scaled(pdf, factor), 21)
        check = normalisation_check(float(cells.values.sum()), cells.error)
        assert check.passed is ok, (factor, check.summary)


# --- chi-square on a Beckmann sampler with alpha 1 % off ---------------------------------------------

BECKMANN_SAMPLES = 1_000_000


def test_beckmann_alpha_one_percent_off_fails_chi2():
    for seed in (0, 1):
        result = check_warp(beckmann_sample(0.303), beckmann_pdf(0.3), "hemisphere", seed=seed,
                            samples=BECKMANN_SAMPLES)
        assert result.checks["chi2"].passed is False, result.checks["chi2"].summary
        assert result.checks["normalisation"].passed


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_exact_beckmann_passes_chi2(seed):
    result = check_warp(beckmann_sample(0.3), beckmann_pdf(0.3), "hemisphere", seed=seed, samples=BECKMANN_SAMPLES)
    assert result.checks["chi2"].passed is True, result.checks["chi2"].summary
    assert result.checks["chi2"].details["dof"] == 51 * 51 - 1


# --- regression report ------------------------------------------------------------------------------

def _run(mean, se, passed=True, seconds=1.0):
    return {"integrator": "simple", "scene": "cornell", "pass": passed, "image_mean": list(mean),
            "image_mean_se": list(se), "seconds": {"mcval": {"total": seconds}}, "metrics": {"relmse": 1e-3}}


def _mean_flags(entries):
    (entry,) = entries
    return [f for f in entry["flags"] if f.startswith("image mean moved")]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_regression_flags_a_mean_moved_by_five_sigma_and_not_one(seed):
    rng = np.random.default_rng(seed)
    mean = rng.uniform(0.2, 0.8, 3)
    se0, se1 = rng.uniform(1e-4, 1e-3, 3), rng.uniform(1e-4, 1e-3, 3)
    sigma = np.hypot(se0, se1)
    baseline = {"images": [_run(mean, se0)]}
    for channel in range(3):
        moved = mean.copy()
        moved[channel] += 5 * sigma[channel]
        flags = _mean_flags(compare_runs([_run(moved, se1)], baseline))
        assert flags and "5.0 standard errors" in flags[0], channel
        moved = mean.copy()
        moved[channel] -= 1 * sigma[channel]
        assert not _mean_flags(compare_runs([_run(moved, se1)], baseline)), channel
    # Every channel moved by 5 sigma, and all by just under the threshold.
    assert _mean_flags(compare_runs([_run(mean + 5 * sigma, se1)], baseline))
    assert not _mean_flags(compare_runs([_run(mean + 0.95 * MEAN_SIGMAS * sigma, se1)], baseline))
    assert not _mean_flags(compare_runs([_run(mean, se1)], baseline))


# --- detectable bias --------------------------------------------------------------------------------

def _definition_bias(test, ref, level):
    """The relative bias b (test scaled by 1 + b) that the image-scale test at `level` detects in at
    least one channel with probability IMAGE_POWER_TARGET, channels independent, Welch dof."""
    k1, k2 = len(test), len(ref)
    a, r = test.mean(axis=(1, 2)), ref.mean(axis=(1, 2))
    va, vr = a.var(0, ddof=1) / k1, r.var(0, ddof=1) / k2
    se = np.sqrt(va + vr)
    dof = (va + vr) ** 2 / (va**2 / (k1 - 1) + vr**2 / (k2 - 1))
    crit = sps.t.isf(level / 2, dof)
    scale = np.abs(r.mean(0)) / se

    def excess(b):
        power = sps.nct.sf(crit, dof, b * scale) + np.nan_to_num(sps.nct.cdf(-crit, dof, b * scale))
        return 1 - np.prod(1 - power) - IMAGE_POWER_TARGET
    return brentq(excess, 0.0, 10.0 / scale.max(), xtol=1e-12)


@pytest.mark.parametrize("seed", [0, 1])
def test_detectable_bias_is_its_definition(seed):
    rng = np.random.default_rng(seed)
    test = 0.5 + rng.normal(0, 0.05, (8, 8, 8, 3))
    ref = 0.5 + rng.normal(0, 0.05, (8, 8, 8, 3))
    result = compare_batches(test, ref, rounding=0.0)
    expected = _definition_bias(test, ref, result.scales[2].level)
    assert result.detectable_bias == pytest.approx(expected, rel=1e-3)


def test_a_bias_of_the_detectable_size_is_found_about_half_of_the_time():
    """Comparison.detectable_bias is the relative bias of the image mean (the test scaled by 1 + b) found
    in IMAGE_POWER_TARGET of the runs: planted in replications, the image scale rejects about that often
    (a figure twice too large would be found almost always)."""
    rng = np.random.default_rng(0)
    k, size, reps = 8, 8, 40
    found = 0
    for _ in range(reps):
        test = 0.5 + rng.normal(0, 0.05, (k, size, size, 3))
        ref = 0.5 + rng.normal(0, 0.05, (k, size, size, 3))
        bias = compare_batches(test, ref, rounding=0.0).detectable_bias
        assert 0 < bias < 0.2
        found += not compare_batches(test * (1 + bias), ref, rounding=0.0).scales[2].passed
    assert abs(found / reps - IMAGE_POWER_TARGET) < 0.25, found


# --- efficiency ratio -------------------------------------------------------------------------------

def _noisy_curve(name, error_constant, seconds_per_spp, rng):
    steps = [Step(s, list(seconds_per_spp * s * rng.uniform(0.97, 1.03, 3)),
                  list(error_constant / s * rng.uniform(0.97, 1.03, 3)), [0.1] * 3) for s in (1, 2, 4, 8, 16, 32, 64)]
    return Curve(name, "render only", steps, 0.1)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_efficiency_ratio_of_a_twice_slower_twin(seed):
    rng = np.random.default_rng(seed)
    same = CaseBench(None, {"mcval": _noisy_curve("mcval", 0.4, 0.01, rng),
                            "mitsuba": _noisy_curve("mitsuba", 0.4, 0.01, rng)}, np.zeros(3))
    assert same.efficiency_ratio() == pytest.approx(1.0, rel=0.1)
    # The tested engine twice as slow for the same error: half as efficient (an inverted ratio would say 2).
    slow = CaseBench(None, {"mcval": _noisy_curve("mcval", 0.4, 0.02, rng),
                            "mitsuba": _noisy_curve("mitsuba", 0.4, 0.01, rng)}, np.zeros(3))
    assert slow.efficiency_ratio() == pytest.approx(0.5, rel=0.1)
