"""albedo, an integrator of the test-only renderer build (build/python-test, build/render_with_test_integrators):
the diffuse reflectance of the first hit, 0 on a miss. Its entry reaches the harness through
MCVAL_INTEGRATOR_PATH=tests/plugins/integrators, showing that an integrator is added without editing the harness."""
import numpy as np

from harness.integrators.entry import AnalyticForm, IntegratorEntry, MitsubaMapping

ENTRY = IntegratorEntry(
    name="albedo",
    our_spp=4,
    reference_spp=16,
    # Mitsuba's aov "albedo" is the BSDF's diffuse reflectance at the first hit (3 channels, 0 on a miss, in
    # scalar_rgb and llvm_ad_rgb alike); no emitter changes it.
    mitsuba=MitsubaMapping("aov", (("string", "aovs", "albedo:albedo"),), drop_area_emitters=True),
    analytic=AnalyticForm("the plane's reflectance",
                          lambda scene, p, normal: np.broadcast_to(scene.reflectance, p.shape)),
    linear_in=("reflectance",),  # no emitter changes it
    noisy_where_varying=False,  # constant over each surface, as normals
)
