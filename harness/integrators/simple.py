"""simple: direct light from point lights on diffuse surfaces, shadow rays, nothing else."""
import numpy as np

from harness.closed_forms.sphere import lit
from harness.closed_forms.vectors import dot, sub
from harness.integrators.entry import AnalyticForm, IntegratorEntry, has_point_light


def _point_lights(scene, p: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """L = rho / pi * I * max(0, cos) / r^2 per point light; only a resting sphere can shadow (the floor)."""
    out = np.zeros_like(p)
    for position, intensity in scene.lights:
        to_light = sub(position, p)
        r2 = dot(to_light, to_light)
        cos = np.clip(dot(to_light, normal) / np.sqrt(r2), 0.0, None)
        shadow = lit(scene, p, position)[..., 0]
        scale = scene.reflectance / np.pi * intensity
        for c in range(3):  # a channel at a time (harness/closed_forms/vectors.py)
            out[..., c] += scale[c] * cos / r2 * shadow
    return out


ENTRY = IntegratorEntry(
    name="simple",
    tested_spp=32,
    reference_spp=256,
    # Point lights only: the renderer's loader skips every other emitter under simple, area emitters in shapes included.
    emitters=("point",),
    analytic=AnalyticForm("rho/pi * I * max(0, cos) / r^2 per point light, floor points behind a resting "
                          "sphere dark", _point_lights, scenes=("plane", "sphere_floor")),
    requirements=(("a point light", has_point_light),),
    linear_in=("light", "reflectance"),
)
