"""The comparison's verdict on noise: the test's per-sample variance against the reference's
(harness.statistics.variance_ratio).

Against a reference that draws the same estimator, sample for sample (`same_estimator`: the integrator
entry's Mitsuba mapping), a variance beyond the noise either way fails: the estimator is not the one the
integrator declares (ambient occlusion sampled uniformly and weighted by 2 cos has the mean of the
cosine-weighted one and a larger variance, and passes every test of the mean). Against the same estimator, a
pixel or a tile far noisier than the reference's neighbourhood fails too (harness.statistics.excess_spread): a
firefly, which the image-wide test, a t-test over tiles, cannot see. The two share the check's level (Sidak).
Against any other reference
the ratio is the relative efficiency of the two estimators, reported; a significantly larger variance is a
warning, never a failure.

Public API::

    check = VarianceCheck.of(test, reference, (spp_test, spp_ref), level, same_estimator)   # Summary each
    check.verdict ("PASS", "WARN", "FAIL"), check.passed, check.summary, check.to_json()
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from harness.comparison.outlier_check import CHANNELS
from harness.statistics.constants import sidak_level
from harness.statistics.excess_spread import ExcessSpread, excess_spread
from harness.statistics.variance_ratio import VarianceRatio, variance_ratio

if TYPE_CHECKING:
    from harness.comparison.summary import Summary

#: Up to this many pixels beyond the critical ratio are called fireflies (single samples far off).
FIREFLY_PIXELS = 16


@dataclass(frozen=True)
class VarianceCheck:
    """The whole image's variance ratio, the pixels' and tiles' excess against the same estimator, and what
    they mean here."""

    #: None where the image-wide test cannot be made (see variance_ratio).
    result: VarianceRatio | None
    same_estimator: bool
    #: The per-pixel and per-tile excess; None unless the reference draws the same estimator.
    excess: ExcessSpread | None = None
    #: Why the excess is not tested though the estimator is the same (`heavy_tail`), or "".
    no_excess: str = ""

    @classmethod
    def of(cls, test: Summary, reference: Summary, spp: tuple[int | None, int | None], level: float,
           same_estimator: bool, heavy_tail: str = "") -> VarianceCheck | None:
        """None where the sample counts are unknown or neither test can be made. `heavy_tail`: why the
        estimator's own rare samples lie far above its pixels' means (a light path the reference's neighbourhoods
        meet a few times), where a pixel's variance, estimated from one such sample, says nothing of a firefly:
        the excess is then not tested."""
        if spp[0] is None or spp[1] is None:
            return None
        counts = (spp[0], spp[1])
        tested = same_estimator and not heavy_tail
        each = sidak_level(level, 2) if tested else level
        result = variance_ratio(test.pixel, reference.pixel, counts, each)
        excess = (excess_spread(test.pixel, reference.pixel, test.tile, reference.tile, counts, each)
                  if tested else None)
        no_excess = heavy_tail if same_estimator else ""
        return None if result is None and excess is None else cls(result, same_estimator, excess, no_excess)

    @property
    def verdict(self) -> str:
        if self.excess is not None and self.excess.rejects:
            return "FAIL"
        r = self.result
        if r is None or not r.rejects:
            return "PASS"
        if self.same_estimator:
            return "FAIL"
        return "WARN" if r.ratio > 1.0 else "PASS"

    @property
    def passed(self) -> bool:
        return self.verdict != "FAIL"

    @property
    def summary(self) -> str:
        """One line, e.g. "per-sample variance 1.31x the reference's (p = 2e-40; same estimator: must be 1)";
        a firefly first."""
        if self.excess is not None and self.excess.rejects:
            s = self.excess.worst_scale
            where = "pixel" if s.scale == "pixel" else "8x8 tile at"
            # A few pixels: fireflies; more, or tiles alone: an estimator noisier than the one declared, in places.
            what = "firefly" if s.scale == "pixel" and s.failures <= FIREFLY_PIXELS else "noise beyond the estimator's"
            return (f"{what}: the test's {where} (row {s.worst[0]}, column {s.worst[1]}, {CHANNELS[s.worst[2]]}) "
                    f"has {s.ratio:.3g}x the per-sample variance of the reference's neighbourhood (at most "
                    f"{s.critical:.3g}x without a defect; {s.failures} {s.scale}s beyond it): a batch far off "
                    "where the same estimator's samples never stray so far")
        r = self.result
        if r is None:
            return "no firefly: every pixel and tile within the reference's noise (the image-wide test not made)"
        what = (f"per-sample variance {r.ratio:.3g}x the reference's (p = {r.p_value:.2g}, level {r.level:.2g}; "
                f"a ratio of {r.found_half:.3g} is found half of the time)")
        if self.same_estimator:
            untested = f"; fireflies not tested: {self.no_excess}" if self.no_excess else ""
            return what + ("; the same estimator: the ratio must be 1" if not self.passed else "") + untested
        return what + ("; another estimator: its efficiency is lower" if self.verdict == "WARN" else
                       "; another estimator: reported, not judged")

    def to_json(self) -> dict:
        return {**(self.result.to_json() if self.result else {}), "same_estimator": self.same_estimator,
                "excess": self.excess.to_json() if self.excess else None, "no_excess": self.no_excess,
                "verdict": self.verdict,
                "summary": self.summary}
