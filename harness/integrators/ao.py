"""ao: ambient occlusion under a constant environment (radiance 1 when the scene has none)."""
from harness.closed_forms.sphere import ao_visible
from harness.closed_forms.vectors import times
from harness.integrators.entry import UNUSED_EMITTERS, AnalyticForm, IntegratorEntry, MitsubaMapping


def _several_rays(root) -> str | None:
    """Our ao traces the file's `samples` occlusion rays per camera sample; Mitsuba's mapping one BSDF sample."""
    integrator = root.find("integrator")
    rays = next((e.get("value") for e in (integrator if integrator is not None else [])
                 if e.get("name") == "samples"), "1")
    return None if rays == "1" else f"{rays} occlusion rays per camera sample"

ENTRY = IntegratorEntry(
    name="ao",
    our_spp=32,
    reference_spp=256,
    # Direct light from the environment alone: every other emitter goes, as our loader skips them. One BSDF
    # sample and no emitter sample: the diffuse BSDF samples the cosine-weighted hemisphere, so each sample is
    # rho * L_env * V, our estimator sample for sample (Mitsuba's default adds an emitter sample under MIS).
    mitsuba=MitsubaMapping("direct", (("boolean", "hide_emitters", "true"), ("integer", "emitter_samples", "0"),
                                      ("integer", "bsdf_samples", "1")),
                           drop_emitters=("point", *UNUSED_EMITTERS), drop_area_emitters=True, add_environment=True),
    analytic=AnalyticForm("rho * L_env * V: V = 1 on a lone plane; 1 - (R/D)^3 on the floor under a resting "
                          "sphere, (1 + n.up)/2 on the sphere",
                          lambda scene, p, normal: times(scene.reflectance * scene.environment,
                                                         ao_visible(scene, p, normal)),
                          scenes=("plane", "sphere_floor"),
                          # One cosine-weighted occlusion ray per camera sample, as ours and Mitsuba's direct.
                          sample=lambda scene, p, normal, u: times(scene.reflectance * scene.environment,
                                                                   u < ao_visible(scene, p, normal))),
    linear_in=("light", "reflectance"),
    default_environment=True,
    same_estimator_in_mitsuba=True,
    estimator_differs=_several_rays,
)
