"""A budget from a target: the samples per pixel at which a case's comparison finds a stated relative bias of
the image mean POWER_TARGET (90 %) of the time (`--detect-bias 0.5%`).

A pilot render of the tested engine at the integrator's default budget gives the noise per sample; a batch
of n samples has that noise over n, so the comparison's power model (the noncentral t of the image scale,
harness.statistics.detectable_bias, at the run's level, against the case's reference) is evaluated for
candidate n, and the smallest n whose 90 %-power bias is at most the target is chosen (bisection; the
bias falls as n grows). The batches stay IMAGE_BATCHES. Where even an unlimited budget could not reach the
target, the reference's own noise is what limits it, and the plan says so instead of rendering. What the
run will cost is the pilot's render time scaled by n over the pilot's samples.
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

from harness.comparison.summary import summarize
from harness.engines.base import Engine
from harness.images.case_task import draws_tested_estimator
from harness.images.references import load_reference, render_params, render_reference
from harness.images.suite import ImageCase
from harness.integrators import entry
from harness.images.spp_search import MAX_SPP, pooled, smallest_spp
from harness.statistics.constants import IMAGE_BATCHES

@dataclass(frozen=True)
class Budget:
    """One case's plan: None for `spp` where the target cannot be reached, with the reason."""

    case: str
    target: float
    pilot_spp: int
    #: The 90 %-power bias at the pilot's budget, and at the chosen one.
    pilot_bias: float
    planned_bias: float
    spp: int | None
    batches: int
    #: The render seconds the chosen budget should take (the pilot's, scaled).
    seconds: float
    reason: str = ""

    @property
    def line(self) -> str:
        if self.spp is None:
            return f"{self.case}: {self.reason}"
        return (f"{self.case}: a bias of {self.target:.3g} is found 90 % of the time at {self.spp} spp x "
                f"{self.batches} batches (planned {self.planned_bias:.3g}; {self.pilot_spp} spp finds "
                f"{self.pilot_bias:.3g}); about {self.seconds:.1f} s of rendering")

    def to_json(self) -> dict:
        return dataclasses.asdict(self)


def plan_budget(case: ImageCase, tested: Engine, reference: Engine, target: float, alpha: float,
                seed: int) -> Budget:
    """The budget of `case` for a bias `target` (relative, e.g. 0.005) at the run's per-comparison `alpha`."""
    ref, _ = load_reference(case, reference)
    if ref is None:
        ref = render_reference(case, reference)
    pilot_spp = case.test_spp
    start = time.perf_counter()
    result = tested.render(str(case.path), case.integrator, pilot_spp, IMAGE_BATCHES, seed, render_params(case))
    render_seconds = result.seconds.get("render", time.perf_counter() - start)
    pilot = pooled(summarize(result.batches))
    reference_summary = pooled(ref.summary)
    signed = entry(case.integrator).signed
    same = draws_tested_estimator(case, tested, reference)
    found = smallest_spp(pilot, pilot_spp, reference_summary, ref.spp, target, alpha, signed, same)
    if found.spp is None:
        return Budget(case.key, target, pilot_spp, found.pilot_bias, found.planned_bias, None, IMAGE_BATCHES, 0.0,
                      f"a bias of {target:.3g} cannot be found 90 % of the time against this reference: even "
                      f"{MAX_SPP} spp finds only {found.planned_bias:.3g} (the reference's own noise; a reference "
                      "with more samples would)")
    return Budget(case.key, target, pilot_spp, found.pilot_bias, found.planned_bias, found.spp, IMAGE_BATCHES,
                  render_seconds * found.spp / pilot_spp)


def parse_bias(text: str) -> float:
    """"0.5%" -> 0.005, "0.005" -> 0.005; ValueError for anything else or outside (0, 1)."""
    value = float(text[:-1]) / 100.0 if text.strip().endswith("%") else float(text)
    if not 0.0 < value < 1.0:
        raise ValueError(f"a relative bias between 0 and 1 (or 0% and 100%) was expected, not {text!r}")
    return value
