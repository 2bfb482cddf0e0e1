"""Our `microfacet` (Nori's, renderer/bsdfs/nori_microfacet.cpp) passes every check of its own at normal, oblique
and grazing incidence, seeds 0-2, for a pure specular lobe and a mixture; Mitsuba has no such plugin, so Nori's own
tests stand in for a reference (tests/bsdfs/test_nori_tests.py)."""
import pytest

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import CHECKS, STATISTICAL, check_bsdf_at
from harness.bsdfs.suite import row_angles
from harness.engines.bsdf_library import BsdfLibrary
from harness.statistics.constants import sidak_level
from tests.helpers.bsdf_libraries import OURS

SPECULAR = {"alpha": 0.1, "kd": 0.0, "ks": 1.0, "int_ior": 1.33, "ext_ior": 1.01}
MIXED = {"alpha": 0.6, "kd": 0.25, "ks": 0.6, "int_ior": 1.8, "ext_ior": 1.3}
ANGLES = (0.0, 60.0, 89.0)
LEVEL = sidak_level(0.01, len(STATISTICAL) * len(ANGLES) * 2)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_microfacet_passes_every_check(seed):
    ours = BsdfLibrary(OURS)
    for values in (SPECULAR, MIXED):
        bsdf = ours.functions("microfacet", values)
        assert row_angles(bsdf, ANGLES) == list(ANGLES)  # a reflector: no rows from below
        for theta in ANGLES:
            results = check_bsdf_at(bsdf, incident(theta), 50_000, seed, LEVEL)
            assert {n: r.verdict for n, r in results.items()} == dict.fromkeys(CHECKS, "PASS"), \
                (bsdf.label, theta, {n: r.summary for n, r in results.items()})
