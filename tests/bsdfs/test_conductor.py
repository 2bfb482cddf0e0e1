"""Smooth conductors, a BSDF of one delta lobe (harness/bsdfs/delta.py): ours passes every check, its delta
samples mirrored and its lobe's expected weight (the Fresnel reflectance) Mitsuba's, at normal, oblique and
grazing incidence and seeds 0-2; a mirror that forgets to turn wi around, one without Fresnel and one that gives
Mitsuba's internal pdf of 1 for its delta sample fail the check that names each."""
import numpy as np
import pytest

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import CHECKS, DELTA_CHECKS, REFERENCE_CHECKS, STATISTICAL, check_bsdf_at
from harness.engines.bsdf_library import BsdfLibrary
from harness.statistics.constants import sidak_level
from tests.helpers.bsdf_libraries import OURS, assert_every_check_passes

pytestmark = pytest.mark.mitsuba

GOLD = {"eta": 0.2, "k": 3.0, "specular_reflectance": 1.0}
MIRROR = {"eta": 0.0, "k": 1.0, "specular_reflectance": 0.7}
ANGLES = (0.0, 60.0, 89.0)
LEVEL = sidak_level(0.01, len(STATISTICAL) * len(ANGLES) * 2)
SAMPLES = 20_000


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_conductor_passes_every_check_against_mitsubas(mitsuba, seed):
    ours = BsdfLibrary(OURS)
    for values in (GOLD, MIRROR):
        for theta in ANGLES:
            results = assert_every_check_passes(ours.functions("conductor", values), theta, SAMPLES, seed, LEVEL,
                                                mitsuba.functions("conductor", values))
            fresnel = results["reference delta weights"].details["reflection"]["here"]
            assert 0 < fresnel <= values["specular_reflectance"] + 1e-6


def test_a_mirror_that_does_not_turn_wi_around_fails_its_delta_lobes(delta_twins):
    results = check_bsdf_at(delta_twins.functions("unturned_mirror", {}), incident(60.0), SAMPLES, 0, LEVEL)
    assert results["delta lobes"].verdict == "FAIL" and "not the mirror direction" in results["delta lobes"].summary
    assert all(results[n].verdict == "PASS" for n in CHECKS)


def test_a_conductor_without_fresnel_fails_its_delta_weights_against_mitsubas(delta_twins, mitsuba):
    results = check_bsdf_at(delta_twins.functions("conductor", GOLD), incident(60.0), SAMPLES, 0, LEVEL,
                            mitsuba.functions("conductor", GOLD))
    assert results["reference delta weights"].verdict == "FAIL", results["reference delta weights"].summary
    assert all(results[n].verdict == "PASS" for n in CHECKS + DELTA_CHECKS + REFERENCE_CHECKS)


def test_a_delta_sample_with_a_finite_pdf_fails_its_weight(delta_twins):
    results = check_bsdf_at(delta_twins.functions("finite_pdf_mirror", {}), incident(30.0), SAMPLES, 0, LEVEL)
    assert results["weight"].verdict == "FAIL" and "delta lobes" not in results
    assert np.isnan(results["sampling"].p_value) or results["sampling"].verdict == "FAIL"
