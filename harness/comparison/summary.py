"""What a comparison needs of K batch renders: per-scale means and variances (pixel, 8x8 tile, image), the
smallest value of each pixel, and the evidence on the batches' independence and on a batch that stands apart. Stored references keep the means
and variances only (harness/images/references.py).

Public API::

    summary = summarize(batches)   # (K, H, W, 3)
    summary.pixel, summary.tile, summary.image, summary.mean_image
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from harness.statistics.constants import TILE_SIZE
from harness.statistics.independence import BatchDependence, batch_dependence
from harness.statistics.outlier_batch import BatchOutlier, batch_outlier
from harness.statistics.welch import BatchStats

#: Bumped whenever `summarize` changes what it stores, so stored references are made again.
SUMMARY_FORMAT = 3


@dataclass
class Summary:
    """What the tests need of K batches: per-scale means and variances, and the mean image."""

    pixel: BatchStats     # (H, W, 3)
    tile: BatchStats      # (H/tile, W/tile, 3)
    image: BatchStats     # (3,)
    tile_size: int
    #: (H, W, 3) smallest batch value per pixel, for the finite check (a negative value in one batch);
    #: None for stored summaries, which keep only means and variances.
    minimum: np.ndarray | None = field(default=None, repr=False)
    #: Whether the batches are independent (harness.statistics.independence); None for stored summaries.
    dependence: BatchDependence | None = None
    #: The batch whose image mean stands furthest from the others' (harness.statistics.outlier_batch); None for
    #: stored summaries and where no batch can be judged.
    outlier: BatchOutlier | None = None

    @property
    def mean_image(self) -> np.ndarray:
        return self.pixel.mean


def tile_means(x: np.ndarray, tile: int) -> np.ndarray:
    """(K, H, W, C) -> (K, ceil(H/tile), ceil(W/tile), C) means; edge tiles average what they hold.

    A NaN or infinite pixel makes its tile's mean non-finite (it is not skipped)."""
    k, h, w, c = x.shape
    th, tw = -(-h // tile), -(-w // tile)
    padded = np.zeros((k, th * tile, tw * tile, c))
    padded[:, :h, :w] = x
    inside = np.zeros((th * tile, tw * tile))
    inside[:h, :w] = 1.0
    counts = inside.reshape(th, tile, tw, tile).sum(axis=(1, 3))
    return padded.reshape(k, th, tile, tw, tile, c).sum(axis=(2, 4)) / counts[None, :, :, None]


def summarize(batches: np.ndarray, tile: int = TILE_SIZE) -> Summary:
    """Summary of (K, H, W, 3) batches (K >= 2): unbiased means and variances of the means."""
    b = np.asarray(batches, np.float64)
    if b.ndim != 4 or b.shape[-1] != 3:
        raise ValueError(f"expected (K, H, W, 3) batches, got shape {b.shape}")
    if b.shape[0] < 2:
        raise ValueError("at least 2 batches are needed to estimate a variance")
    with np.errstate(invalid="ignore", over="ignore"):  # NaN and Inf propagate; the finite check reports them
        image = b.mean(axis=(1, 2))
        return Summary(BatchStats.of(b), BatchStats.of(tile_means(b, tile)), BatchStats.of(image),
                       tile, b.min(axis=0), batch_dependence(b), batch_outlier(image))
