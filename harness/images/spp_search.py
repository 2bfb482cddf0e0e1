"""The smallest samples per pixel at which a comparison finds a stated relative bias of the image mean, from a
render's summary at hand: each variance of the summary scales as one over the samples per batch, and the
comparison's power model (harness.statistics.detectable_bias) is evaluated at candidate budgets (bisection; the
bias falls as the budget grows). Used by `--detect-bias` (harness/images/budget.py) and by an INCONCLUSIVE
comparison to say what would decide it."""
from __future__ import annotations

import dataclasses

import numpy as np

from harness.comparison.compare import compare_summaries
from harness.comparison.independence_check import constant_image
from harness.comparison.summary import Summary
from harness.statistics.constants import INCONCLUSIVE_BIAS
from harness.statistics.welch import BatchStats

#: The most samples per pixel per batch a budget asks for.
MAX_SPP = 1 << 16


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


def at_spp(pilot: Summary, pilot_spp: int, spp: int) -> Summary:
    """The pilot's summary as a render of `spp` samples per batch would give it: every variance times pilot/spp."""
    factor = pilot_spp / spp
    return dataclasses.replace(pilot, pixel=_scaled(pilot.pixel, factor), tile=_scaled(pilot.tile, factor),
                               image=_scaled(pilot.image, factor), minimum=None, dependence=None, outlier=None)


@dataclasses.dataclass(frozen=True)
class SppFound:
    """The smallest budget that reaches the target (None where even MAX_SPP does not), and the biases found."""

    spp: int | None
    #: The bias found at the pilot's budget, at the chosen one (at MAX_SPP where none reaches the target).
    pilot_bias: float
    planned_bias: float


def smallest_spp(pilot: Summary, pilot_spp: int, reference: Summary, reference_spp: int, target: float,
                 alpha: float, signed: bool, same_estimator: bool, most: bool = True) -> SppFound:
    """The smallest spp at which the image-mean bias `target` is found 90 % of the time (`most`) or half of the
    time (not `most`), against `reference` at the per-comparison `alpha`. Pass pooled summaries."""

    def found(spp: int) -> float:
        c = compare_summaries(at_spp(pilot, pilot_spp, spp), reference, alpha, signed=signed,
                              samples=(spp, reference_spp), metrics=False, same_estimator=same_estimator,
                              tile_power=False)
        return c.detectable_bias_most if most else c.detectable_bias

    pilot_bias, best = found(pilot_spp), found(MAX_SPP)
    if not best <= target:
        return SppFound(None, pilot_bias, best)
    lo, hi = 0, MAX_SPP  # found(lo) > target (or lo = 0), found(hi) <= target
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if found(mid) <= target else (mid, hi)
    return SppFound(hi, pilot_bias, found(hi))


def decisive_budget(summary: Summary, spp: int, reference: Summary, reference_spp: int, alpha: float, signed: bool,
                    same_estimator: bool) -> str:
    """One line on the samples per pixel at which the comparison would resolve INCONCLUSIVE_BIAS, or why no
    budget would (no signal; the reference's own noise)."""
    if constant_image(summary) and constant_image(reference):
        return "no budget decides an image without signal: show the camera something to shade"
    found = smallest_spp(pooled(summary), spp, pooled(reference), reference_spp, INCONCLUSIVE_BIAS, alpha, signed,
                         same_estimator, most=False)
    if found.spp is None:
        return (f"no budget of the engine under test decides it: even {MAX_SPP} spp finds only "
                f"{found.planned_bias:.3g} against this reference's noise (a reference with more samples would)")
    return (f"{found.spp} spp a batch would decide it (half of the time; `--detect-bias {INCONCLUSIVE_BIAS:.0%}` "
            "plans for 90 %)")

