"""path: path tracing with next-event estimation, multiple importance sampling and Russian roulette (Mitsuba 3's
`path`). Its image is not linear in the reflectance (light bounces more than once), only in the light."""
from harness.closed_forms import furnace
from harness.integrators.direct import EMITTERS, has_emitter
from harness.integrators.entry import AnalyticForm, IntegratorEntry

ENTRY = IntegratorEntry(
    name="path",
    tested_spp=16,
    reference_spp=256,
    emitters=EMITTERS,
    # Mitsuba's defaults: no limit on the path's vertices, Russian roulette from the fifth bounce on.
    parameters=(("integer", "max_depth", "-1"), ("integer", "rr_depth", "5")),
    # A furnace's image is known; its noise is not modelled (draws_estimator False: the mean is judged).
    analytic=AnalyticForm("Le (1 + a + ... + a^(d-1)) in a furnace of reflectance a, max_depth d (Le / (1 - a) "
                          "without a limit)", None, scenes=(), furnace=furnace.path_radiance,
                          draws_estimator=False),
    requirements=(("an emitter", has_emitter),),
    linear_in=("light",),
)
