"""Whether a base render can show an invariance: its signal, and the independence of its batches.

A cell compares each rewritten scene's image, mapped back, with the base's. Two bases make that mean nothing:

* **No signal.** Every value of every batch is 0 (a camera that sees nothing lit, a renderer that writes black).
  Each rewrite maps 0 to 0, so every renderer would pass: the cell is INCONCLUSIVE, not judged, unless a
  variant fails, which is evidence all the same. A constant image of another value is judged: the value must
  stay, or scale, under the rewrites (a ray offset that darkens a lone plane at scale 10^-3 shows there).
* **Batches that are one image.** The K batches, rendered at K distinct seeds, agree exactly, where the
  integrator's estimate changes with the seed wherever its image varies (IntegratorEntry.noisy_where_varying)
  and this image varies at ALIKE_MIN_FRACTION of its values or more: the renderer did not use its seed. The
  comparison divides by the batches' spread, zero here, so it would pass what it should not: the cell FAILs.
  An integrator whose varying image may be noiseless (normals) is judged so only against a reference engine
  that draws the same estimator (harness/invariance/reference_noise.py), as the image suite judges it.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from harness.comparison.independence_check import ALIKE_MIN_ELEMENTS, ALIKE_MIN_FRACTION, varying_elements
from harness.comparison.summary import Summary
from harness.integrators.entry import IntegratorEntry
from harness.statistics.welch import rounding_floor
from harness.statistics.independence import BatchDependence

NO_SIGNAL = "the base render is constant (all 0): an invariance cannot be judged on an image without signal"


def structure(mean: np.ndarray) -> int:
    """Values (pixel and channel) of an (H, W, C) image that differ from their channel's median beyond float
    rounding: 0 for an image constant in each channel."""
    m = np.asarray(mean, np.float64)
    median = np.median(m, axis=(0, 1))
    floor = rounding_floor(m, at=median)
    with np.errstate(invalid="ignore"):
        return int(np.count_nonzero(np.abs(m - median) > floor))


def widely(count: int, elements: int) -> bool:
    """Whether `count` of `elements` values is as wide as the image suite's test of batches all alike asks."""
    return count >= max(ALIKE_MIN_ELEMENTS, ALIKE_MIN_FRACTION * elements)


@dataclass(frozen=True)
class BaseSignal:
    """What a cell's base render shows: its size, where its batches vary, where its image varies."""

    batches: int
    #: Values of one image (pixels x channels).
    elements: int
    #: Values whose batches differ beyond float rounding; 0 when every batch is the same image.
    varying: int
    #: Values that differ from their channel's median (`structure`); 0 for an image constant in each channel.
    varied: int
    #: Every value of every batch is 0.
    zero: bool
    #: The batches' dependence evidence (harness.statistics.independence), for the check against a reference
    #: engine; kept in memory only (None for a stored cell, or when the batches are not finite).
    dependence: BatchDependence | None = field(default=None, compare=False, repr=False)

    @classmethod
    def of(cls, batches: np.ndarray, summary: Summary) -> BaseSignal:
        """The signal of (K, H, W, C) base batches and their summary."""
        return cls(int(batches.shape[0]), int(summary.pixel.mean.size), varying_elements(summary),
                   structure(summary.pixel.mean), bool(np.all(batches == 0)), summary.dependence)

    @property
    def no_signal(self) -> str | None:
        """Why no invariance can be judged on this base, or None."""
        return NO_SIGNAL if self.zero else None

    @property
    def alike(self) -> bool:
        """Every batch is the same image."""
        return self.dependence is not None and self.dependence.varying == 0

    def unused_seed(self, integrator: IntegratorEntry) -> str | None:
        """Why the batches show that the renderer did not use its seed, or None (see the module's docstring)."""
        if not (self.alike and integrator.noisy_where_varying and widely(self.varied, self.elements)):
            return None
        return (f"batches not independent: all {self.batches} batches of the base render are the same image, though "
                f"{integrator.name}'s estimate changes with the seed wherever its image varies (here at "
                f"{self.varied} of {self.elements} pixel values): is the seed it is given used?")

    def to_json(self) -> dict:
        return {"batches": self.batches, "elements": self.elements, "varying": self.varying, "varied": self.varied,
                "zero": self.zero}

    @classmethod
    def from_json(cls, d: dict) -> BaseSignal:
        return cls(int(d["batches"]), int(d["elements"]), int(d["varying"]), int(d["varied"]), bool(d["zero"]))
