"""What the benchmark measures each engine's error against. Where physics gives the image (a closed form:
a lone plane, a sphere resting on a floor), the analytic engine's render decides; elsewhere the stored
Mitsuba reference. A biased reference would otherwise count its own bias as the other engine's error:
at the 1e-3 scale Mitsuba breaks the sphere's closed form, and an engine that holds it would converge to
Mitsuba's bias instead of to zero."""
from __future__ import annotations

from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine
from harness.images.references import (REFERENCE_BATCHES, REFERENCE_SEED, RESOLUTION, Reference, load_reference,
                                        render_reference)
from harness.comparison.summary import summarize
from harness.images.suite import ImageCase

def bench_truth(case: ImageCase, reference_engine: Engine, spp: int) -> tuple[Reference, str]:
    """The image `case`'s errors are measured against, and one line saying what it is; `spp`: the analytic
    engine's per batch, the ladder's last step (its 16 batches are then 16 times that step, and the relMSE
    subtracts the rest of the truth's own variance)."""
    params = {"res": str(RESOLUTION)}
    if AnalyticEngine.supports(str(case.path), params, case.integrator):
        result = AnalyticEngine().render(str(case.path), case.integrator, spp, REFERENCE_BATCHES, REFERENCE_SEED,
                                         params)
        return (Reference(summarize(result.batches), spp, result.seconds, "closed form"),
                f"closed form (analytic engine, {REFERENCE_BATCHES} x {spp} spp)")
    reference, _ = load_reference(case, reference_engine)
    if reference is None:
        reference = render_reference(case, reference_engine)
    return reference, f"{reference_engine.version()} reference ({reference.spp} spp x {REFERENCE_BATCHES}, {reference.source})"
