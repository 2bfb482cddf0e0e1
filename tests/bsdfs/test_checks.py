"""The checks of a BSDF (harness/bsdfs/checks.py) on a correct Lambertian BSDF, ours and a C library's, at
several seeds and incident directions, and on its known-wrong twins (tests/bsdfs/bsdf_twins.c): each twin
fails the check that names its mistake."""
import numpy as np
import pytest

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import CHECKS, STATISTICAL, check_bsdf_at
from harness.statistics.constants import sidak_level

SAMPLES = 100_000
ANGLES = (0.0, 60.0, 89.0)
#: The per-test level of a run of these BSDFs at these angles, at a family-wise 0.01.
LEVEL = sidak_level(0.01, len(STATISTICAL) * len(ANGLES) * 2)



def _verdicts(bsdf, theta: float, seed: int) -> dict[str, str]:
    return {name: r.verdict for name, r in check_bsdf_at(bsdf, incident(theta), SAMPLES, seed, LEVEL).items()}


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_correct_lambertian_passes_every_check(twins, seed):
    """(Ours, diffuse, passes them too, against Mitsuba's: tests/bsdfs/test_reference.py.)"""
    theirs = twins.functions("lambert", {"albedo": 0.7})
    for theta in ANGLES:
        assert _verdicts(theirs, theta, seed) == dict.fromkeys(CHECKS, "PASS"), (theirs.label, theta)


@pytest.mark.parametrize("twin, check", [
    ("no_inv_pi", "energy"),                # value and weight pi too large: an albedo of 0.5 pi
    ("weight_no_cosine", "weight"),         # weight = albedo / cos theta_o where value / pdf = albedo
    ("uniform_pdf", "sampling"),            # samples the cosine, says uniform
    ("one_sided_shadowing", "reciprocity"),  # a factor of wo alone
    ("nan_on_the_normal", "hard inputs"),   # wi's azimuth normalised by its sine: 0 / 0 with wi on the normal
    ("unguarded_sampler", "hard inputs"),   # z = sqrt(u): value / pdf is 0 / 0 at u = 0
])
def test_each_twin_fails_the_check_that_names_it(twins, twin, check):
    results = check_bsdf_at(twins.functions(twin, {"albedo": 0.5}), incident(30.0), SAMPLES, 0, LEVEL)
    assert [n for n, r in results.items() if r.verdict == "FAIL"] == [check], {n: r.summary for n, r in results.items()}


@pytest.mark.parametrize("twin, shown", [
    ("alpha_for_alpha2", "p = 0"),  # D with alpha where alpha^2 belongs, its sampler right: a wider lobe than drawn
    ("no_jacobian", "pdf integrates to"),  # pdf = D(h) cos theta_h, without dh/dwo = 1 / (4 wo.h): not a density of wo
    ("ggx_sampled", "p = 0"),  # GGX's normals drawn, Beckmann's evaluated
])
def test_each_microfacet_twin_fails_where_its_sampler_and_pdf_part(microfacet_twins, twin, shown):
    """Each computes its weight as its own value / pdf, so the weight holds: the sampling check names the mistake
    (and the normalisation, as the share of failed samples no longer matches the pdf's integral)."""
    correct = check_bsdf_at(microfacet_twins.functions("beckmann", {"alpha": 0.3}), incident(30.0), SAMPLES, 0, LEVEL)
    assert {n: r.verdict for n, r in correct.items()} == dict.fromkeys(CHECKS, "PASS")
    results = check_bsdf_at(microfacet_twins.functions(twin, {"alpha": 0.3}), incident(30.0), SAMPLES, 0, LEVEL)
    failed = [n for n, r in results.items() if r.verdict == "FAIL"]
    assert failed == ["sampling", "normalisation"], {n: r.summary for n, r in results.items()}
    assert shown in results["sampling" if shown == "p = 0" else "normalisation"].summary


def test_the_cells_come_from_a_pilot_draw_and_a_small_run_is_judged(twins):
    """The cells are the quantiles of a pilot drawn apart; 5,000 samples get 17 x 17 of them (16 a cell), not 51 x 51
    pooled into one."""
    lambert = twins.functions("lambert", {"albedo": 0.5})
    sampling = check_bsdf_at(lambert, incident(30.0), SAMPLES, 0, LEVEL)["sampling"]
    assert sampling.verdict == "PASS" and sampling.details["binning"] == "pilot quantiles"
    small = check_bsdf_at(lambert, incident(30.0), 5000, 0, LEVEL)["sampling"]
    assert small.verdict == "PASS" and small.details["dof"] > 200, small.details
    wrong = check_bsdf_at(twins.functions("uniform_pdf", {"albedo": 0.5}), incident(30.0), 5000, 0, LEVEL)["sampling"]
    assert wrong.verdict == "FAIL"


def test_the_energy_check_states_the_excess_it_finds(twins):
    energy = check_bsdf_at(twins.functions("one_sided_shadowing", {"albedo": 0.5}), incident(30.0), SAMPLES, 0,
                           LEVEL)["energy"]
    assert energy.verdict == "PASS" and 0 < energy.details["detectable_excess"] < 0.01, energy.details


def test_a_bsdf_that_draws_nothing_is_not_judged_a_pass(twins):
    results = check_bsdf_at(twins.functions("draws_nothing", {"albedo": 0.5}), incident(30.0), SAMPLES, 0, LEVEL)
    assert results["sampling"].verdict == "FAIL" and "no sample was drawn" in results["sampling"].summary


@pytest.mark.parametrize("share, off, verdict", [(2e-5, 5e-3, "PASS"), (1e-3, 5e-3, "FAIL"), (2e-5, 0.05, "FAIL")])
def test_a_few_sampled_pdfs_off_by_rounding_pass_and_more_fail(share, off, verdict):
    """Float32 rounding of wo near a glass's critical angle moves a few sampled pdfs past 10^-3 of pdf(): up to
    10^-4 of the samples within 10^-2 pass (saying so); more samples, or farther, fail."""
    from harness.bsdfs.boundary import uniform_lambert
    from harness.engines.base import BsdfFunctions

    lambert = uniform_lambert(0.8)

    def sample(wi, u):
        wo, weight, pdf = lambert.sample(wi, u)
        k = int(share * len(u))
        return wo, weight, np.concatenate([pdf[:k] * (1 + off), pdf[k:]])

    bsdf = BsdfFunctions("rounded", lambert.params, lambert.eval, lambert.pdf, sample)
    weight = check_bsdf_at(bsdf, incident(30.0), SAMPLES, 0, LEVEL)["weight"]
    assert weight.verdict == verdict, weight.summary
    assert (verdict == "PASS") == ("float32 rounding" in weight.summary)


@pytest.mark.parametrize("where, verdict", [("below", "PASS"), ("above", "FAIL")])
def test_a_references_pdf_is_compared_where_a_value_is_not_zero(where, verdict):
    """A reference with a density where neither BSDF scatters light (Mitsuba's roughplastic below the surface) is
    not a difference of the tested BSDF's, and is counted; a density off where light is scattered fails."""
    from harness.bsdfs.boundary import uniform_lambert
    from harness.bsdfs.reference import values_check
    from harness.engines.base import BsdfFunctions

    lambert = uniform_lambert(0.8)

    def pdf(wi, wo):
        stray = (wo[:, 2] < 0) if where == "below" else (wo[:, 2] > 0.5)
        return lambert.pdf(wi, wo) + 0.1 * stray

    reference = BsdfFunctions("stray", lambert.params, lambert.eval, pdf, lambert.sample)
    result = values_check(lambert, reference, incident(30.0), 10_000, 0)
    assert result.verdict == verdict, result.summary
    assert (result.details["reference_pdf_without_value"] > 0) == (where == "below")
