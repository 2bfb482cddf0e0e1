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

import numpy as np

from harness.comparison.compare import compare_summaries
from harness.comparison.summary import Summary, summarize
from harness.engines.base import Engine
from harness.images.case_task import draws_our_estimator
from harness.images.references import load_reference, render_params, render_reference
from harness.images.suite import OUR_SPP, ImageCase
from harness.integrators import entry
from harness.statistics.constants import IMAGE_BATCHES
from harness.statistics.welch import BatchStats

#: The most samples per pixel per batch a budget asks for.
MAX_SPP = 1 << 16


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


def _scaled(stats: BatchStats, factor: float) -> BatchStats:
    return BatchStats(stats.mean, np.asarray(stats.var_of_mean) * factor, stats.k, stats.dof)


def pooled(summary: Summary) -> Summary:
    """The summary with its image mean's variance taken from its tiles': the image mean is the tiles' means
    weighted by their pixels, and tiles are nearly independent, so sum_t (n_t / N)^2 var_t estimates it with
    hundreds of times the K - 1 degrees of freedom of the image's own K batch means. The power model needs
    the noise itself, not one draw of it: planned from the image's own variance, a 0.5 % target was found
    99 % of the time instead of 90 %."""
    h, w = summary.pixel.mean.shape[:2]
    size = summary.tile_size
    rows = np.minimum(size, h - size * np.arange(summary.tile.mean.shape[0]))
    cols = np.minimum(size, w - size * np.arange(summary.tile.mean.shape[1]))
    weight = (rows[:, None] * cols[None, :] / float(h * w))[..., None]
    var = np.sum(weight**2 * np.asarray(summary.tile.var_of_mean, np.float64), axis=(0, 1))
    return dataclasses.replace(summary, image=BatchStats(summary.image.mean, var, summary.image.k, summary.image.dof))


def _at(pilot: Summary, pilot_spp: int, spp: int) -> Summary:
    """The pilot's summary as a render of `spp` samples per batch would give it: every variance times pilot/spp."""
    factor = pilot_spp / spp
    return dataclasses.replace(pilot, pixel=_scaled(pilot.pixel, factor), tile=_scaled(pilot.tile, factor),
                               image=_scaled(pilot.image, factor), minimum=None, dependence=None)


def plan_budget(case: ImageCase, ours: Engine, reference: Engine, target: float, alpha: float,
                seed: int) -> Budget:
    """The budget of `case` for a bias `target` (relative, e.g. 0.005) at the run's per-comparison `alpha`."""
    ref, _ = load_reference(case, reference)
    if ref is None:
        ref = render_reference(case, reference)
    pilot_spp = OUR_SPP[case.integrator]
    start = time.perf_counter()
    result = ours.render(str(case.path), case.integrator, pilot_spp, IMAGE_BATCHES, seed, render_params(case))
    render_seconds = result.seconds.get("render", time.perf_counter() - start)
    pilot = pooled(summarize(result.batches))
    reference_summary = pooled(ref.summary)
    signed = entry(case.integrator).signed
    same = draws_our_estimator(case, reference.name)

    def found(spp: int) -> float:
        c = compare_summaries(_at(pilot, pilot_spp, spp), reference_summary, alpha, signed=signed,
                              samples=(spp, ref.spp), metrics=False, same_estimator=same)
        return c.detectable_bias_most

    pilot_bias, best = found(pilot_spp), found(MAX_SPP)
    if not best <= target:
        return Budget(case.key, target, pilot_spp, pilot_bias, best, None, IMAGE_BATCHES, 0.0,
                      f"a bias of {target:.3g} cannot be found 90 % of the time against this reference: even "
                      f"{MAX_SPP} spp finds only {best:.3g} (the reference's own noise; a reference with "
                      "more samples would)")
    lo, hi = 0, MAX_SPP  # found(lo) > target (or lo = 0), found(hi) <= target
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if found(mid) <= target else (mid, hi)
    return Budget(case.key, target, pilot_spp, pilot_bias, found(hi), hi, IMAGE_BATCHES,
                  render_seconds * hi / pilot_spp)


def parse_bias(text: str) -> float:
    """"0.5%" -> 0.005, "0.005" -> 0.005; ValueError for anything else or outside (0, 1)."""
    value = float(text[:-1]) / 100.0 if text.strip().endswith("%") else float(text)
    if not 0.0 < value < 1.0:
        raise ValueError(f"a relative bias between 0 and 1 (or 0% and 100%) was expected, not {text!r}")
    return value
