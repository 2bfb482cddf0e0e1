"""An engine's base batches that are all one image, judged against a reference engine that draws the same
estimator, as the image suite judges them (harness.comparison.independence_check): where the reference's base
batches of the same case vary at ALIKE_MIN_FRACTION of the values or more, the engine did not use its seed.
This reaches what harness/invariance/signal.py leaves alone: an integrator whose varying image may be
noiseless (normals), whose noise, along edges, a reference with the same estimator shows.
"""
from __future__ import annotations

from harness.comparison.independence_check import SideIndependence
from harness.images.case_task import MITSUBA_MAPPED
from harness.integrators import entry
from harness.invariance.cell import Cell


def judge_against_references(cells: list[Cell]) -> None:
    """Set `dependence` on each cell of an engine not mapped through Mitsuba whose base batches are one image
    where a Mitsuba-mapped engine's base of the same case, drawing the same estimator there
    (IntegratorEntry.same_estimator), varies widely."""
    references = [c for c in cells if c.engine in MITSUBA_MAPPED and c.base is not None]
    for cell in cells:
        if cell.engine in MITSUBA_MAPPED or cell.dependence or cell.base is None or not cell.base.alike:
            continue
        if not entry(cell.case.integrator).same_estimator(cell.case.scene):
            continue
        for ref in (r for r in references if r.case.key == cell.case.key):
            side = SideIndependence(cell.base.dependence, ref.base.varying, cell.base.elements, judge_alike=True)
            if side.alike:
                cell.dependence = (f"batches not independent: all {cell.base.batches} batches of the base render are "
                                   f"the same image, where {ref.engine}'s, drawing the same estimator, vary at "
                                   f"{ref.base.varying} pixel values: is the seed it is given used?")
                break
