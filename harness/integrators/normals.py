"""normals: the shading normal of the first hit, signed, 0 on a miss."""
import numpy as np

from harness.integrators.entry import AnalyticForm, IntegratorEntry

ENTRY = IntegratorEntry(
    name="normals",
    tested_spp=16,
    reference_spp=64,
    # Emitters and BSDFs cannot change a normal: it reads no emitter (an envmap's missing image cannot fail it).
    aov="sh_normal",
    analytic=AnalyticForm("the surface's normal (the plane's; (p - c)/R on a sphere)",
                          lambda scene, p, normal: np.broadcast_to(normal, p.shape),
                          scenes=("plane", "sphere_floor")),
    signed=True,
    checks_geometry=True,
    noisy_where_varying=False,
    rotates_with_scene=True,
    benchmarked=False,
)
