"""Is the test's estimator as noisy as the reference's? The per-sample variance of the whole image, compared.

Each side's per-sample variance at an element (pixel and channel) is estimated from its batches: a batch of n
samples has variance sigma^2 / n, so v = n K var_of_mean = n s^2 (s^2 the sample variance of the K batch
means) is unbiased for sigma^2 whatever the estimator's distribution (binary occlusion at 32 spp included),
and so is the difference D = v_test - v_ref of two sides that draw the same estimator. Elements are summed
per 8 x 8 tile (TILE_SIZE: a pixel filter correlates neighbours, tiles are nearly independent) and the tile
sums of D are tested for mean 0 with a one-sample t-test over the tiles, two-sided: a larger variance is a
worse estimator (uniform hemisphere sampling weighted by 2 cos where the cosine-weighted one is expected),
a smaller one an estimator that is not the one declared or batches that share samples. The t-test on tile
sums is the calibrated choice here, not an F-test on each pixel: K = 8 batch means of a binary estimator
are far from Gaussian, and an F-test's level then depends on their kurtosis, which a tile's sum of 192
elements averages away (tests/statistics/test_variance_ratio.py measures the level on such nulls).

The reported `ratio` is sum v_test / sum v_ref: the test's per-sample variance over the reference's, 1 for
the same estimator, the reference's efficiency over the test's at equal time per sample. The power figures
are the ratios the test finds half of the time and POWER_TARGET of the time, from the noncentral t of the
same test (a ratio r moves the mean of D by (r - 1) sum v_ref).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from harness.statistics.constants import POWER_TARGET, TILE_SIZE
from harness.statistics.distributions import nct_sf, t_isf, t_sf
from harness.statistics.tiles import tile_blocks
from harness.statistics.welch import BatchStats, beyond_rounding

#: Tiles needed for the t-test over tiles to mean anything.
MIN_TILES = 8


@dataclass(frozen=True)
class VarianceRatio:
    """The per-sample variance of the test's estimator over the reference's, over the whole image."""

    ratio: float
    p_value: float
    level: float
    tiles: int
    #: The ratios (above 1) this test finds half of the time and POWER_TARGET of the time.
    found_half: float
    found_most: float

    @property
    def rejects(self) -> bool:
        return self.p_value < self.level

    def to_json(self) -> dict:
        return {"ratio": self.ratio, "p_value": self.p_value, "level": self.level, "tiles": self.tiles,
                "found_half_of_the_time": self.found_half, "found_90_percent": self.found_most,
                "rejects": self.rejects}


def per_sample_variance(stats: BatchStats, spp: int) -> np.ndarray:
    """n K var_of_mean: an unbiased estimate of the per-sample variance of each element; 0 where the batch
    means spread no more than float rounding of the values does (`beyond_rounding`)."""
    return np.where(beyond_rounding(stats), spp * stats.k * np.asarray(stats.var_of_mean, np.float64), 0.0)


def _ratio_found(power: float, base: float, se: float, dof: float, critical: float) -> float:
    """The smallest ratio r >= 1 that the test finds with probability `power` (a root of the noncentral t's
    power, bracketed by doubling; hi where the power is not reached below 1e6)."""
    if not (base > 0 and se > 0):
        return float("inf")

    def excess(r: float) -> float:
        return float(nct_sf(critical, dof, (r - 1.0) * base / se)) - power

    lo, hi = 1.0, 2.0
    above = excess(hi)
    while above < 0.0 and hi < 1e6:
        lo, hi = hi, 2.0 * hi
        above = excess(hi)
    if not above >= 0.0:
        return hi
    # At r = 1 the test rejects at its level, below any power asked for. As close as 40 halvings of [lo, hi]
    # would come, in a few steps.
    return float(brentq(excess, lo, hi, xtol=(hi - lo) * 2.0 ** -42, rtol=1e-15))


def variance_ratio(test: BatchStats, reference: BatchStats, spp: tuple[int, int], level: float,
                   tile: int = TILE_SIZE) -> VarianceRatio | None:
    """The whole-image variance test between two sides' pixel statistics (H, W, C) rendered at `spp` samples
    per batch; None where it cannot be made (non-finite values, fewer than MIN_TILES tiles, no variance)."""
    vt, vr = per_sample_variance(test, spp[0]), per_sample_variance(reference, spp[1])
    if vt.ndim != 3 or not (np.isfinite(vt).all() and np.isfinite(vr).all()):
        return None
    dt, dr = tile_blocks(vt, tile).sum(axis=-1), tile_blocks(vr, tile).sum(axis=-1)
    d = dt - dr
    tiles = d.size
    total_ref = float(dr.sum())
    if tiles < MIN_TILES or not total_ref > 0:
        return None
    sd = float(d.std(ddof=1))
    se = sd / np.sqrt(tiles)
    dof = float(tiles - 1)
    if not se > 0:
        return None
    t = float(d.mean()) / se
    p = float(min(1.0, 2.0 * t_sf(abs(t), dof)))
    critical = float(t_isf(level / 2.0, dof))
    base = total_ref / tiles  # the mean tile sum of the reference: a ratio r moves mean(d) by (r - 1) base
    return VarianceRatio(float(dt.sum()) / total_ref, p, level, tiles,
                         _ratio_found(0.5, base, se, dof, critical), _ratio_found(POWER_TARGET, base, se, dof, critical))
