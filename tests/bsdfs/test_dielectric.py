"""Smooth dielectrics, two delta lobes seen from both sides (harness/bsdfs/delta.py): ours passes every check
against Mitsuba's, from above and below, at normal, oblique and grazing incidence (total internal reflection
from inside) and seeds 0-2, its energy counted as flux; a glass without the radiance scale eta^2 fails its energy
and its delta weights against Mitsuba's, and one bending by eta where 1 / eta belongs fails Snell's law."""
import pytest

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import STATISTICAL, check_bsdf_at
from harness.bsdfs.suite import row_angles
from harness.engines.bsdf_library import BsdfLibrary
from harness.statistics.constants import sidak_level
from tests.helpers.bsdf_libraries import OURS, assert_every_check_passes

pytestmark = pytest.mark.mitsuba

GLASS = {"int_ior": 1.5, "ext_ior": 1.0}
ANGLES = (0.0, 30.0, 89.0)
LEVEL = sidak_level(0.01, len(STATISTICAL) * len(ANGLES) * 2)
SAMPLES = 20_000


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_dielectric_passes_every_check_against_mitsubas_from_both_sides(mitsuba, seed):
    ours = BsdfLibrary(OURS).functions("dielectric", GLASS)
    angles = row_angles(ours, ANGLES)
    assert angles == [0.0, 30.0, 89.0, 180.0, 150.0, 91.0]
    for theta in angles:
        results = assert_every_check_passes(ours, theta, SAMPLES, seed, LEVEL, mitsuba.functions("dielectric", GLASS))
        lobes = results["reference delta weights"].details
        if theta == 91.0:  # from inside, beyond the critical angle: all reflected
            assert lobes["refraction"]["here"] == 0 and lobes["reflection"]["here"] == 1


def test_a_glass_without_the_radiance_scale_fails_energy_and_delta_weights(delta_twins, mitsuba):
    results = check_bsdf_at(delta_twins.functions("dielectric", GLASS), incident(0.0), SAMPLES, 0, LEVEL,
                            mitsuba.functions("dielectric", GLASS))
    failed = sorted(n for n, r in results.items() if r.verdict == "FAIL")
    assert failed == ["energy", "reference delta weights"], {n: r.summary for n, r in results.items()}


def test_a_glass_bending_by_the_inverse_index_fails_snells_law(delta_twins):
    results = check_bsdf_at(delta_twins.functions("snell_inverted", GLASS), incident(30.0), SAMPLES, 0, LEVEL)
    failed = sorted(n for n, r in results.items() if r.verdict == "FAIL")
    # Bent by 1.5 where 1 / 1.5 belongs, a grazing wi's tangent outgrows 1: no unit vector is left to draw.
    assert failed == ["delta lobes", "hard inputs"], {n: r.summary for n, r in results.items()}
    assert "miss Snell's angle for eta = 1.5" in results["delta lobes"].summary
    assert "not unit vectors" in results["hard inputs"].summary
