"""Is the test far noisier, somewhere, than the reference that draws the same estimator? A firefly (one batch
of one pixel off by orders of magnitude, as a broken MIS weight or a pdf wrong near a singularity writes it)
inflates the test's own variance, so Welch's test divides it away and the image-wide variance test, a t-test
over tiles, is swamped by the one tile that holds it. This test looks at each element on its own.

At each pixel (and channel) the test's per-sample variance v_t = n K var_of_mean is held against the
reference's, taken as the largest over the pixel's SPREAD_WINDOW x SPREAD_WINDOW neighbourhood: a pixel's
samples come from its footprint, whose variance its neighbours share, and at an edge or beside a rare
contribution (a shadow sliver that the reference's batches saw once) the neighbourhood's largest holds what
the pixel's own estimate can miss. The same is done for 8 x 8 tiles (the variance of a tile's mean, its
neighbourhood in tiles). A variance at the level of float rounding of the values is never an excess.

Under the null, with Gaussian batch means, v_t / sigma^2 is chi^2(K - 1) / (K - 1) and the neighbourhood's
largest is at least sigma^2 up to its own noise (reference batches: 16), so F = v_t / max is at most an
F(K_t - 1, K_r - 1) variate: the test rejects above its quantile at the level over all elements (Bonferroni),
which is conservative where the neighbourhood is noisier than the pixel. Heavy-tailed estimators (a point
light at grazing angles, a light close to a surface) are measured by `calibrate`; the window keeps them
below the quantile. A firefly 10x a pixel's value gives F of 10^2 to 10^8 (docs/statistics.md).

Public API::

    excess = excess_spread(test.pixel, reference.pixel, test.tile, reference.tile, (spp_t, spp_r), level)
    excess.rejects, excess.worst_scale, excess.worst, excess.ratio, excess.critical
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import maximum_filter
from scipy.special import fdtri

from harness.statistics.constants import SPREAD_WINDOW, TILE_SIZE
from harness.statistics.tiles import tile_blocks
from harness.statistics.welch import BatchStats, rounding_floor

#: The rate (times 1 / N) below which a contribution none of N reference samples met is taken to lie: N samples
#: miss one of rate 10 / N with probability e^-10 = 4.5e-5. A test batch that met it h times then shows a
#: variance ratio of about h^2 / 6; it takes six hits (while the reference, with 16 times the samples, met none)
#: to reach a pixel's critical ratio, which happens below 1e-8 per pixel at any rate.
MISSED_RATE = 10.0


@dataclass(frozen=True)
class ScaleSpread:
    """One scale's largest variance ratio, where it is, and how many elements reject."""

    scale: str
    ratio: float
    #: (row, column) in pixels of the largest ratio (a tile's top-left corner at the tile scale), its channel.
    worst: tuple[int, int, int]
    critical: float
    failures: int

    def to_json(self) -> dict:
        return {"scale": self.scale, "ratio": self.ratio, "worst": list(self.worst), "critical": self.critical,
                "failures": self.failures}


@dataclass(frozen=True)
class ExcessSpread:
    """Pixel and tile scales; rejects when any element's ratio exceeds its scale's critical value."""

    scales: tuple[ScaleSpread, ...]
    level: float

    @property
    def rejects(self) -> bool:
        return any(s.failures for s in self.scales)

    @property
    def worst_scale(self) -> ScaleSpread:
        """The finest scale that rejects, else the one closest to rejecting."""
        rejecting = [s for s in self.scales if s.failures]
        return rejecting[0] if rejecting else max(self.scales, key=lambda s: s.ratio / s.critical)

    def to_json(self) -> dict:
        return {"level": self.level, "rejects": self.rejects, "scales": [s.to_json() for s in self.scales]}


def _ratios(test: BatchStats, reference: BatchStats, spp: tuple[int, int], window: int, largest: np.ndarray,
            pixels: int) -> np.ndarray:
    """Per element: the test's per-sample variance over the largest of the reference's in the neighbourhood,
    floored at what a contribution that the reference's samples all missed may add (`largest`: the largest
    reference pixel value the element's samples may take; `pixels` of them in the element), and at the
    variance that float rounding of the values would show."""
    rounding = rounding_floor(test.mean)
    vt = spp[0] * test.k * np.asarray(test.var_of_mean, np.float64)
    vr = spp[1] * reference.k * np.asarray(reference.var_of_mean, np.float64)
    vr = maximum_filter(np.where(np.isfinite(vr), vr, 0.0), size=(window, window, 1), mode="nearest")
    # A contribution of value up to `largest` that none of the reference's N samples met has a rate below
    # MISSED_RATE / N, so a per-sample variance below MISSED_RATE largest^2 / N at a pixel (over the pixels of a
    # tile) is no excess: an occluder one test batch met once, 0.58 among batches of 0.6, where the reference's
    # neighbourhood met none.
    missed = MISSED_RATE * np.square(largest) / (spp[1] * reference.k * pixels)
    # Noise at the level of rounding (a batch mean's spread within ROUNDING_TOLERANCE of its value) is no excess.
    floor = np.maximum(spp[0] * rounding * rounding, missed)
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        return vt / np.maximum(vr, np.maximum(floor, np.finfo(np.float64).tiny))


def _largest(values: np.ndarray, window: int) -> np.ndarray:
    """The largest finite |value| of each element's window x window neighbourhood, over every channel: a
    sample's channels share its scale (a normal whose G is 0 about a box's edge has R or B near 1, and the rare
    sample on the box's top gives G a 1)."""
    v = np.abs(np.asarray(values, np.float64))
    channels = v.shape[-1]
    return maximum_filter(np.where(np.isfinite(v), v, 0.0), size=(window, window, channels), mode="nearest")


def _scale(name: str, ratios: np.ndarray, upsample: int, critical: float) -> ScaleSpread:
    clean = np.where(np.isnan(ratios), 0.0, ratios)
    idx = np.unravel_index(int(np.argmax(clean)), clean.shape)
    return ScaleSpread(name, float(clean[idx]), (int(idx[0]) * upsample, int(idx[1]) * upsample, int(idx[2])),
                       critical, int(np.count_nonzero(clean > critical)))


def excess_spread(test_pixel: BatchStats, reference_pixel: BatchStats, test_tile: BatchStats,
                  reference_tile: BatchStats, spp: tuple[int, int], level: float,
                  tile: int = TILE_SIZE, window: int = SPREAD_WINDOW) -> ExcessSpread | None:
    """The per-pixel and per-tile variance ratios of (H, W, C) statistics rendered at `spp` samples per batch,
    each scale tested at half of `level` (Bonferroni over its elements); None for fewer than 2 batches a side
    or statistics that are not images."""
    if np.ndim(test_pixel.mean) != 3 or test_pixel.k < 2 or reference_pixel.k < 2:
        return None
    half = level / 2.0
    pixel_largest = _largest(reference_pixel.mean, window)
    # A tile's: the largest reference pixel in it, then over its 3 x 3 tiles.
    in_tile = tile_blocks(np.abs(np.nan_to_num(np.asarray(reference_pixel.mean, np.float64))), tile)
    th, tw = np.shape(reference_tile.mean)[:2]
    channels = np.shape(reference_pixel.mean)[2]
    tile_largest = _largest(in_tile.max(axis=1).reshape(th, tw, 1).repeat(channels, axis=2), 3)
    scales = []
    for name, t, r, upsample, win, largest, pixels in (
            ("pixel", test_pixel, reference_pixel, 1, window, pixel_largest, 1),
            ("tile", test_tile, reference_tile, tile, 3, tile_largest, tile * tile)):
        ratios = _ratios(t, r, spp, win, largest, pixels)
        critical = float(fdtri(t.k - 1, r.k - 1, 1.0 - half / max(ratios.size, 1)))
        scales.append(_scale(name, ratios, upsample, critical))
    return ExcessSpread(tuple(scales), level)
