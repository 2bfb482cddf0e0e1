"""Pixels no image may hold: NaN, +Inf, -Inf, and negative values where the image must be non-negative.

A NaN or an infinity makes every statistic built on it meaningless (a NaN standard
error is no evidence of agreement), so a comparison checks both sides for them
before any statistics and fails on any such pixel, through a check of its own.
Radiance, irradiance and occlusion are never negative; only `normals` is signed.

Public API::

    check = FiniteCheck(damage_of_summary(test, signed), damage_of_summary(reference, signed), signed)
    check.passed, check.summary, check.to_json()
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import reduce
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from harness.comparison.summary import Summary

#: How many (row, column) locations of bad pixels a check keeps, per kind and side (row-major order).
MAX_LOCATIONS = 20
SIDES = ("test", "reference")


@dataclass
class Damage:
    """The bad pixels of one side's image, counted per pixel (any batch, any channel)."""

    #: Pixels holding a NaN, +Inf or -Inf.
    nonfinite: int
    #: Pixels holding a finite negative value (0 for signed images).
    negative: int
    #: (row, column) of the first MAX_LOCATIONS pixels of each kind, row-major.
    nonfinite_at: list[tuple[int, int]]
    negative_at: list[tuple[int, int]]
    #: (H, W) True where a pixel is bad in either way.
    mask: np.ndarray = field(repr=False)

    @property
    def clean(self) -> bool:
        return self.nonfinite == 0 and self.negative == 0

    @property
    def locations(self) -> list[tuple[int, int]]:
        """The first MAX_LOCATIONS bad pixels of either kind, row-major."""
        return sorted(set(self.nonfinite_at) | set(self.negative_at))[:MAX_LOCATIONS]


def per_pixel(op: np.ufunc, x: np.ndarray) -> np.ndarray:
    """op.reduce(x, axis=-1), over the few channels of (..., C) values: numpy reduces a short last axis about ten
    times slower than it combines the channels' slices."""
    return reduce(op, (x[..., c] for c in range(x.shape[-1])))


def _locations(mask: np.ndarray) -> list[tuple[int, int]]:
    rows, cols = np.nonzero(mask)
    return [(int(r), int(c)) for r, c in zip(rows[:MAX_LOCATIONS], cols[:MAX_LOCATIONS])]


def _damage(nonfinite: np.ndarray, negative: np.ndarray) -> Damage:
    return Damage(int(nonfinite.sum()), int(negative.sum()), _locations(nonfinite), _locations(negative),
                  nonfinite | negative)


def damage_of_summary(summary: Summary, signed: bool = False) -> Damage:
    """Bad pixels of a summary: a non-finite pixel mean or variance, a negative variance, or (unless
    `signed`) a negative value in any batch (`summary.minimum`; the pixel mean where a stored summary
    has no minimum). A tile or image statistic that is non-finite while the pixels are not (a damaged
    stored summary) marks the tile's top-left pixel, or pixel (0, 0) for the image."""
    mean, var = summary.pixel.mean, summary.pixel.var_of_mean
    finite = np.isfinite(mean) & np.isfinite(var)
    nonfinite = ~per_pixel(np.logical_and, finite)
    bad_var = per_pixel(np.logical_or, np.where(finite, var, 0.0) < 0)
    low = mean if summary.minimum is None else summary.minimum
    below = np.where(finite & np.isfinite(low), low, 0.0) < 0
    negative = bad_var if signed else bad_var | per_pixel(np.logical_or, below)
    if not nonfinite.any():
        t = summary.tile
        tiles = ~(np.isfinite(t.mean) & np.isfinite(t.var_of_mean)).all(axis=-1)
        h, w, size = mean.shape[0], mean.shape[1], summary.tile_size
        for r, c in zip(*np.nonzero(tiles)):
            nonfinite[min(r * size, h - 1), min(c * size, w - 1)] = True
        if not (np.isfinite(summary.image.mean).all() and np.isfinite(summary.image.var_of_mean).all()):
            nonfinite[0, 0] = True
    return _damage(nonfinite, negative)


@dataclass
class FiniteCheck:
    """Both sides' bad pixels; passes only when neither side has any."""

    test: Damage
    reference: Damage
    #: Negative values were allowed (normals); only changes the wording of `summary`.
    signed: bool = False

    @property
    def passed(self) -> bool:
        return self.test.clean and self.reference.clean

    @property
    def side(self) -> str | None:
        """"test", "reference", "both", or None when both are clean."""
        bad = [name for name in SIDES if not getattr(self, name).clean]
        return None if not bad else bad[0] if len(bad) == 1 else "both"

    @property
    def summary(self) -> str:
        """One line, e.g. "non-finite pixels: 12 in the test image, first at (3, 7)"."""
        parts = []
        for name in SIDES:
            d: Damage = getattr(self, name)
            if d.nonfinite:
                parts.append(f"non-finite pixels: {d.nonfinite} in the {name} image, first at {d.nonfinite_at[0]}")
            if d.negative:
                parts.append(f"negative pixels: {d.negative} in the {name} image (must be non-negative), "
                             f"first at {d.negative_at[0]}")
        return "; ".join(parts) or "every pixel finite" + ("" if self.signed else " and non-negative")

    def to_json(self) -> dict:
        """{"pass", "side", "nonfinite", "negative" (totals over both sides), "locations" (of the first
        bad side), "summary", and per side {"nonfinite", "negative", "locations"}}."""
        first = next((getattr(self, n) for n in SIDES if not getattr(self, n).clean), self.test)
        per_side = {n: {"nonfinite": getattr(self, n).nonfinite, "negative": getattr(self, n).negative,
                        "locations": [list(x) for x in getattr(self, n).locations]} for n in SIDES}
        return {"pass": self.passed, "side": self.side,
                "nonfinite": self.test.nonfinite + self.reference.nonfinite,
                "negative": self.test.negative + self.reference.negative,
                "locations": [list(x) for x in first.locations], "summary": self.summary, **per_side}

