"""The checks of a BSDF (harness/bsdfs/checks.py) on a correct Lambertian BSDF, ours and a C library's, at
several seeds and incident directions, and on its known-wrong twins (tests/bsdfs/bsdf_twins.c): each twin
fails the check that names its mistake."""
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


def test_the_energy_check_states_the_excess_it_finds(twins):
    energy = check_bsdf_at(twins.functions("one_sided_shadowing", {"albedo": 0.5}), incident(30.0), SAMPLES, 0,
                           LEVEL)["energy"]
    assert energy.verdict == "PASS" and 0 < energy.details["detectable_excess"] < 0.01, energy.details


def test_a_bsdf_that_draws_nothing_is_not_judged_a_pass(twins):
    results = check_bsdf_at(twins.functions("draws_nothing", {"albedo": 0.5}), incident(30.0), SAMPLES, 0, LEVEL)
    assert results["sampling"].verdict == "FAIL" and "no sample was drawn" in results["sampling"].summary
