"""Are one side's K batches independent? The mean test takes the spread of K batch means for the noise of
their mean, which holds only when the batches are independent: a renderer that ignores the seed it is given
renders K copies of one image (no spread at all), one whose sampler repeats across batches renders pairs
that agree more than chance allows (too little spread). Either way the mean test would pass what it should
not, so this is checked first.

The statistic looks at the batches' residuals r_k = x_k - mean over k, element by element (pixel and
channel), each element's residual vector scaled to unit length (z_k = r_k / |r|), so that every element
counts alike whatever its noise and its distribution (binary occlusion at 32 spp included). For
exchangeable batches, E[z_j z_k] = -1 / (K (K - 1)) exactly for j != k, whatever the distribution: the
pooled residual correlation of two independent batches is -1 / (K - 1); of two identical batches it is 1.
Elements are not independent (a pixel filter spreads a sample over neighbours), so the sum of a pair's
products is tested with square blocks of DEPENDENCE_CLUSTER pixels as clusters (wider than the pixel
filters that correlate neighbours, small enough that a 32 x 32 image has 64 of them): for the most
correlated pair, z = sum_c S_c / sqrt(sum_c S_c^2), where S_c is the block's sum of z_j z_k less its
null expectation (a self-normalised sum, standard normal for many blocks under the null; it cannot
exceed sqrt(blocks), so a tiny image cannot show dependence), one-sided, Bonferroni over the
K (K - 1) / 2 pairs. A pair is called dependent only when it is both significant at DEPENDENCE_LEVEL and
correlated by at least DEPENDENCE_CORRELATION: a pair that shares a few samples barely changes the mean
test's noise and is not what this check is for, and the floor keeps a block size that is too small for
some filter from turning into false alarms.

Batches that are all alike where noise is expected cannot be tested this way (no element varies); the
comparison (harness.comparison.independence_check) calls them dependent when the other side varies.
Batches that are all correlated alike (each shares a common part) keep the residual correlations of
independent ones: only a variance test against a reference with the same estimator sees them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.statistics.constants import DEPENDENCE_CLUSTER, DEPENDENCE_CORRELATION, DEPENDENCE_LEVEL
from harness.statistics.distributions import norm_sf
from harness.statistics.tiles import tile_blocks
from harness.statistics.welch import BatchStats, beyond_rounding


@dataclass(frozen=True)
class BatchDependence:
    """The evidence of one side's batches: the pair that agrees most beyond chance."""

    batches: int
    #: Elements (pixel and channel) whose batches differ beyond float rounding; 0 when all batches agree.
    varying: int
    #: Blocks holding a varying element (the clusters of the test).
    blocks: int
    #: The pair (0-based batch indices) with the largest test statistic, its pooled residual correlation
    #: (-1 / (K - 1) for independent batches, 1 for identical ones) and its p-value (Bonferroni over pairs).
    pair: tuple[int, int]
    correlation: float
    p_value: float

    @property
    def independent_correlation(self) -> float:
        """The pooled residual correlation two independent batches have."""
        return -1.0 / (self.batches - 1)

    @property
    def dependent(self) -> bool:
        """A pair of batches agrees far beyond chance (identical batches all alike are judged elsewhere)."""
        return self.p_value < DEPENDENCE_LEVEL and self.correlation >= DEPENDENCE_CORRELATION

    def to_json(self) -> dict:
        return {"batches": self.batches, "varying": self.varying, "blocks": self.blocks, "pair": list(self.pair),
                "correlation": self.correlation, "independent_correlation": self.independent_correlation,
                "p_value": self.p_value, "dependent": self.dependent}


def batch_dependence(batches: np.ndarray, tile: int = DEPENDENCE_CLUSTER) -> BatchDependence | None:
    """The dependence evidence of (K, H, W, C) batches; None for fewer than 3 batches (two residuals are
    always opposite) or non-finite values (the finite check fails those)."""
    b = np.asarray(batches, np.float64)
    k = b.shape[0]
    if k < 3 or not np.isfinite(b).all():
        return None
    mean = b.mean(axis=0)
    r = b - mean
    norm2 = (r * r).sum(axis=0)
    varying = beyond_rounding(BatchStats(mean, norm2 / (k * (k - 1)), k))
    count = int(np.count_nonzero(varying))
    if count == 0:
        return BatchDependence(k, 0, 0, (0, 1), float("nan"), 1.0)
    z = np.where(varying, r / np.sqrt(np.where(varying, norm2, 1.0)), 0.0)
    zt = np.moveaxis(tile_blocks(z, tile), 0, -1)                 # (T, n, K)
    per_tile = tile_blocks(varying[None], tile)[0].sum(axis=-1)    # (T,) varying elements a block
    live = per_tile > 0
    zt, per_tile = zt[live], per_tile[live]
    gram = np.matmul(np.swapaxes(zt, 1, 2), zt)                   # (T, K, K): each tile's sums of z_j z_k
    centred = gram + per_tile[:, None, None] / (k * (k - 1))     # less the null mean -1 / (K (K - 1)) each
    total, spread = centred.sum(axis=0), np.sqrt((centred * centred).sum(axis=0))
    with np.errstate(divide="ignore", invalid="ignore"):
        stat = np.where(spread > 0, total / spread, 0.0)
    pooled = gram.sum(axis=0)
    diagonal = pooled.diagonal()
    with np.errstate(divide="ignore", invalid="ignore"):
        correlation = pooled / np.sqrt(np.outer(diagonal, diagonal))
    pairs = np.triu_indices(k, 1)
    best = int(np.argmax(np.nan_to_num(correlation[pairs], nan=-1.0)))
    j, m = int(pairs[0][best]), int(pairs[1][best])
    p = min(1.0, float(norm_sf(stat[j, m])) * len(pairs[0]))
    return BatchDependence(k, count, int(live.sum()), (j, m), float(correlation[j, m]), p)
