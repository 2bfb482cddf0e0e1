"""ao: ambient occlusion under a constant environment (radiance 1 when the scene has none)."""
import numpy as np

from harness.integrators.entry import AnalyticForm, IntegratorEntry, MitsubaMapping

ENTRY = IntegratorEntry(
    name="ao",
    our_spp=32,
    reference_spp=256,
    # Direct light from the environment alone: point lights and area emitters go, as our loader skips them.
    mitsuba=MitsubaMapping("direct", (("boolean", "hide_emitters", "true"),), drop_emitters=("point",),
                           drop_area_emitters=True, add_environment=True),
    analytic=AnalyticForm("rho * L_env (nothing occludes a lone plane)",
                          lambda scene, p, normal: np.broadcast_to(scene.reflectance * scene.environment, p.shape)),
)
