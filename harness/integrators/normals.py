"""normals: the shading normal of the first hit, signed, 0 on a miss."""
import numpy as np

from harness.integrators.entry import UNUSED_EMITTERS, AnalyticForm, ImageConvention, IntegratorEntry, MitsubaMapping

ENTRY = IntegratorEntry(
    name="normals",
    our_spp=16,
    reference_spp=64,
    # Emitters and BSDFs cannot change a normal: every emitter goes (an envmap's missing image cannot fail it).
    mitsuba=MitsubaMapping("aov", (("string", "aovs", "nn:sh_normal"),),
                           drop_emitters=("point", "constant", *UNUSED_EMITTERS), drop_area_emitters=True),
    analytic=AnalyticForm("the surface's normal (the plane's; (p - c)/R on a sphere)",
                          lambda scene, p, normal: np.broadcast_to(normal, p.shape),
                          scenes=("plane", "sphere_floor")),
    signed=True,
    checks_geometry=True,
    same_estimator_in_mitsuba=True,
    noisy_where_varying=False,
    rotates_with_scene=True,
    benchmarked=False,
    # Nori's normals integrator returns the normal's absolute value, component by component.
    nori_image=ImageConvention("|n|, each component's absolute value", np.abs),
)
