"""ao: ambient occlusion under a constant environment (radiance 1 when the scene has none), as the seed defines
it: a surface point sees the environment or not, whatever its material."""
from harness.closed_forms.furnace import is_furnace
from harness.closed_forms.sphere import ao_visible
from harness.closed_forms.vectors import times
from harness.integrators.entry import AnalyticForm, IntegratorEntry

ENTRY = IntegratorEntry(
    name="ao",
    tested_spp=32,
    reference_spp=256,
    # Direct light from the environment alone: every other emitter is ignored (the renderer's loader skips them).
    emitters=("constant",),
    # Occlusion rays per camera sample, each cosine-weighted.
    parameters=(("integer", "samples", "1"),),
    analytic=AnalyticForm("L_env * V: V = 1 on a lone plane; 1 - (R/D)^3 on the floor under a resting "
                          "sphere, (1 + n.up)/2 on the sphere",
                          lambda scene, p, normal: times(scene.environment, ao_visible(scene, p, normal)),
                          scenes=("plane", "sphere_floor"),
                          # One cosine-weighted occlusion ray per camera sample, as the renderers' estimator.
                          sample=lambda scene, p, normal, u: times(scene.environment,
                                                                   u < ao_visible(scene, p, normal))),
    linear_in=("light",),
    # It reads no material (every surface white and opaque): a scene's reflectance leaves its image unchanged.
    independent_of=("reflectance",),
    reads_materials=False,
    default_environment=True,
    # Inside a closed sphere no environment reaches a surface: the image is black, which proves nothing.
    requirements=(("a view of the environment",
                   lambda root: "a furnace: the camera is enclosed, no environment reaches it" if is_furnace(root)
                   else None),),
)
