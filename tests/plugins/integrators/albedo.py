"""albedo, an integrator of the test-only renderer build (build/python-test, build/render_with_test_integrators):
the diffuse reflectance of the first hit, 0 on a miss. Its entry reaches the harness through
MCVAL_INTEGRATOR_PATH=tests/plugins/integrators, showing that an integrator is added without editing the harness."""
import numpy as np

from harness.integrators.entry import AnalyticForm, IntegratorEntry

ENTRY = IntegratorEntry(
    name="albedo",
    tested_spp=4,
    reference_spp=16,
    # The BSDF's diffuse reflectance at the first hit (3 channels, 0 on a miss): the AOV "albedo", which no
    # emitter changes. Mitsuba renders it with its aov plugin, without an edit of the harness's engines.
    aov="albedo",
    analytic=AnalyticForm("the plane's reflectance",
                          lambda scene, p, normal: np.broadcast_to(scene.reflectance, p.shape)),
    linear_in=("reflectance",),  # no emitter changes it
    noisy_where_varying=False,  # constant over each surface, as normals
)
