"""path: path tracing with next-event estimation, multiple importance sampling and Russian roulette (Mitsuba 3's
`path`). Its image is not linear in the reflectance (light bounces more than once), only in the light."""
from harness.closed_forms import furnace
from harness.integrators.direct import EMITTERS, has_emitter, no_delta_lights, no_masks
from harness.integrators.entry import AnalyticForm, IntegratorEntry, Strategies

def strategies_agree(root) -> str | None:
    """Where the three estimate one image: no delta light (BSDF samples never find one) and no mask (its holes
    let BSDF samples through and stop shadow rays)."""
    return no_delta_lights(root) or no_masks(root)


#: The light reaching each vertex from emitter samples alone ("ems"), BSDF samples alone ("mats") or both under
#: MIS ("mis", Mitsuba's path): Nori's path_ems, path_mats and path_mis, selected by our renderer's `strategy`.
#: A delta lobe does not keep them apart: "ems" counts the emission a path finds after one (no emitter sample can).
STRATEGIES = Strategies(settings=tuple((name, (("string", "strategy", name),)) for name in ("ems", "mats", "mis")),
                        applies=strategies_agree)

ENTRY = IntegratorEntry(
    name="path",
    tested_spp=16,
    reference_spp=256,
    emitters=EMITTERS,
    # Mitsuba's defaults: no limit on the path's vertices, Russian roulette from the fifth bounce on; and the
    # strategy of the light at each vertex, which only our renderer reads.
    parameters=(("integer", "max_depth", "-1"), ("integer", "rr_depth", "5"), ("string", "strategy", "mis")),
    own_parameters=("strategy",),
    # A furnace's image is known; its noise is not modelled (draws_estimator False: the mean is judged).
    analytic=AnalyticForm("Le (1 + a + ... + a^(d-1)) in a furnace of reflectance a, max_depth d (Le / (1 - a) "
                          "without a limit)", None, scenes=(), furnace=furnace.path_radiance,
                          draws_estimator=False),
    requirements=(("an emitter", has_emitter),),
    strategies=STRATEGIES,
    linear_in=("light",),
)
