"""Our BSDFs against Mitsuba's plugins of the same name (harness/bsdfs/reference.py, Mitsuba in a process of its
own: harness/engines/mitsuba_bsdfs.py): every check of their own and values, pdfs and sampled directions agree,
for both microfacet distributions and both ways of sampling normals, at 30 and 89 degrees and seeds 0-2; a twin judged
against Mitsuba's plugin it claims to be fails there (a diffuse without its 1/pi, GGX where Beckmann is meant)."""
import pytest

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import CHECKS, REFERENCE_CHECKS, STATISTICAL, check_bsdf_at
from harness.engines.bsdf_library import BsdfLibrary
from harness.engines.mitsuba_bsdfs import plugin_spec
from harness.statistics.constants import sidak_level
from tests.helpers.bsdf_libraries import OURS

pytestmark = pytest.mark.mitsuba

CONDUCTOR = {"alpha": 0.3, "eta": 0.2, "k": 3.0, "sample_visible": 1}
BSDFS = [("diffuse", {"reflectance": 0.7}),
         *(("roughconductor", {**CONDUCTOR, "ggx": ggx, "sample_visible": visible}) for ggx in (0, 1) for visible in (0, 1))]
ANGLES = (30.0, 89.0)
LEVEL = sidak_level(0.01, len(STATISTICAL) * len(ANGLES) * len(BSDFS))
SAMPLES = 50_000



@pytest.mark.parametrize("seed", [0, 1, 2])
def test_ours_agree_with_mitsubas_plugins(mitsuba, seed):
    ours = BsdfLibrary(OURS)
    for name, values in BSDFS:
        for theta in ANGLES:
            results = check_bsdf_at(ours.functions(name, values), incident(theta), SAMPLES, seed, LEVEL,
                                    mitsuba.functions(name, values))
            assert {n: r.verdict for n, r in results.items()} == dict.fromkeys(CHECKS + REFERENCE_CHECKS, "PASS"), \
                (name, values, theta, {n: r.summary for n, r in results.items()})


def test_a_diffuse_without_its_inverse_pi_differs_from_mitsubas(mitsuba, twins):
    twin = twins.functions("no_inv_pi", {"albedo": 0.5})
    results = check_bsdf_at(twin, incident(30.0), SAMPLES, 0, LEVEL, mitsuba.functions("diffuse", {"reflectance": 0.5}))
    assert results["reference values"].verdict == "FAIL" and results["reference samples"].verdict == "PASS"
    assert results["reference values"].summary.startswith("value differs from the reference's by 0.68"), \
        results["reference values"].summary  # 1 - 1/pi


def test_ggx_where_beckmann_is_meant_fails_on_values_and_samples(mitsuba):
    ggx = BsdfLibrary(OURS).functions("roughconductor", {**CONDUCTOR, "ggx": 1})
    results = check_bsdf_at(ggx, incident(30.0), SAMPLES, 0, LEVEL,
                            mitsuba.functions("roughconductor", {**CONDUCTOR, "ggx": 0}))
    assert results["reference values"].verdict == "FAIL" and results["reference samples"].verdict == "FAIL"
    assert all(results[n].verdict == "PASS" for n in CHECKS)  # a correct GGX, judged on its own


def test_only_mitsubas_plugins_are_mapped():
    assert plugin_spec("roughconductor", {"alpha": 0.1, "ggx": 0, "eta": 0.2, "sample_visible": 1}) == {
        "type": "roughconductor", "alpha": 0.1, "distribution": "beckmann", "eta": {"type": "rgb", "value": 0.2},
        "sample_visible": True}
    assert plugin_spec("lambert", {"albedo": 0.5}) is None
