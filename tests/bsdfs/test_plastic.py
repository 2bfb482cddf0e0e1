"""Plastic, a delta lobe beside a smooth one: ours passes every check against Mitsuba's, linear and nonlinear, at
normal, oblique and grazing incidence and seeds 0-2 (its diffuse samples against its pdf, its specular ones as a
mirror's, each lobe's share of the weight Mitsuba's), and is not taken for a BSDF that transmits; a plastic without
the coating's 1 / eta^2 fails its values against Mitsuba's."""
import pytest

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import STATISTICAL, check_bsdf_at
from harness.bsdfs.suite import row_angles
from harness.engines.bsdf_library import BsdfLibrary
from harness.statistics.constants import sidak_level
from tests.helpers.bsdf_libraries import OURS, assert_every_check_passes

pytestmark = pytest.mark.mitsuba

LINEAR = {"int_ior": 1.5, "ext_ior": 1.0, "diffuse_reflectance": 0.5, "nonlinear": 0.0}
NONLINEAR = {**LINEAR, "diffuse_reflectance": 0.9, "nonlinear": 1.0}
ANGLES = (0.0, 60.0, 89.0)
LEVEL = sidak_level(0.01, len(STATISTICAL) * len(ANGLES) * 2)
SAMPLES = 50_000


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_plastic_passes_every_check_against_mitsubas(mitsuba, seed):
    ours = BsdfLibrary(OURS)
    for values in (LINEAR, NONLINEAR):
        bsdf = ours.functions("plastic", values)
        assert row_angles(bsdf, ANGLES) == list(ANGLES)  # opaque: no rows from below
        for theta in ANGLES:
            assert_every_check_passes(bsdf, theta, SAMPLES, seed, LEVEL, mitsuba.functions("plastic", values))


def test_a_plastic_without_the_coatings_inverse_eta_squared_fails_its_values(mitsuba, delta_twins):
    twin = delta_twins.functions("plastic", LINEAR)
    results = check_bsdf_at(twin, incident(30.0), SAMPLES, 0, LEVEL, mitsuba.functions("plastic", LINEAR))
    assert results["reference values"].verdict == "FAIL", results["reference values"].summary
    assert results["reference values"].summary.startswith("value differs from the reference's by 0.55")  # 1 - 1/2.25
