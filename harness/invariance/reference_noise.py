"""An engine's base batches that are all one image, judged against a reference engine that draws the same
estimator, as the image suite judges them (harness.comparison.independence_check): where the reference's base
batches of the same case vary at ALIKE_MIN_FRACTION of the values or more, the engine did not use its seed.
This reaches what harness/invariance/signal.py leaves alone: an integrator whose varying image may be
noiseless (normals), whose noise, along edges, a reference with the same estimator shows.
"""
from __future__ import annotations

from collections.abc import Sequence

from harness.comparison.independence_check import SideIndependence
from harness.engines.base import Engine
from harness.invariance.cell import Cell


def judge_against_references(cells: list[Cell], engines: Sequence[Engine]) -> None:
    """Set `dependence` on each cell whose base batches are one image where the base of the same case by one of
    `engines` that draws the integrator's estimator there (Engine.draws_same_estimator) varies widely; the
    cells of such an engine are the evidence, not judged, and neither are those of an engine that draws an
    estimator of its own (Engine.draws_integrator_estimator), which may have no noise at all."""
    by_name = {e.name: e for e in engines}

    def draws(cell: Cell) -> bool:
        engine = by_name.get(cell.engine)
        return engine is not None and engine.draws_same_estimator(cell.case.scene, cell.case.integrator)

    def own_estimator(cell: Cell) -> bool:  # one of its own, whose batches may well be noiseless
        engine = by_name.get(cell.engine)
        return engine is not None and not engine.draws_integrator_estimator(cell.case.integrator)

    references = [c for c in cells if c.base is not None and draws(c)]
    for cell in cells:
        if cell.dependence or cell.base is None or not cell.base.alike or draws(cell) or own_estimator(cell):
            continue
        for ref in (r for r in references if r.case.key == cell.case.key):
            side = SideIndependence(cell.base.dependence, ref.base.varying, cell.base.elements, judge_alike=True)
            if side.alike:
                cell.dependence = (f"batches not independent: all {cell.base.batches} batches of the base render are "
                                   f"the same image, where {ref.engine}'s, drawing the same estimator, vary at "
                                   f"{ref.base.varying} pixel values: is the seed it is given used?")
                break
