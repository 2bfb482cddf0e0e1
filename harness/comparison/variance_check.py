"""The comparison's verdict on noise: the test's per-sample variance against the reference's
(harness.statistics.variance_ratio).

Against a reference that draws the same estimator, sample for sample (`same_estimator`: the integrator
entry's Mitsuba mapping), a variance beyond the noise either way fails: the estimator is not the one the
integrator declares (ambient occlusion sampled uniformly and weighted by 2 cos has the mean of the
cosine-weighted one and a larger variance, and passes every test of the mean). Against any other reference
the ratio is the relative efficiency of the two estimators, reported; a significantly larger variance is a
warning, never a failure.

Public API::

    check = VarianceCheck.of(test.pixel, reference.pixel, (spp_test, spp_ref), level, same_estimator)
    check.verdict ("PASS", "WARN", "FAIL"), check.passed, check.summary, check.to_json()
"""
from __future__ import annotations

from dataclasses import dataclass

from harness.statistics.variance_ratio import VarianceRatio, variance_ratio
from harness.statistics.welch import BatchStats


@dataclass(frozen=True)
class VarianceCheck:
    """The whole image's variance ratio and what it means here."""

    result: VarianceRatio
    same_estimator: bool

    @classmethod
    def of(cls, test: BatchStats, reference: BatchStats, spp: tuple[int | None, int | None], level: float,
           same_estimator: bool) -> VarianceCheck | None:
        """None where the sample counts are unknown or the test cannot be made (see variance_ratio)."""
        if spp[0] is None or spp[1] is None:
            return None
        result = variance_ratio(test, reference, (spp[0], spp[1]), level)
        return None if result is None else cls(result, same_estimator)

    @property
    def verdict(self) -> str:
        r = self.result
        if not r.rejects:
            return "PASS"
        if self.same_estimator:
            return "FAIL"
        return "WARN" if r.ratio > 1.0 else "PASS"

    @property
    def passed(self) -> bool:
        return self.verdict != "FAIL"

    @property
    def summary(self) -> str:
        """One line, e.g. "per-sample variance 1.31x the reference's (p = 2e-40; same estimator: must be 1)"."""
        r = self.result
        what = (f"per-sample variance {r.ratio:.3g}x the reference's (p = {r.p_value:.2g}, level {r.level:.2g}; "
                f"a ratio of {r.found_half:.3g} is found half of the time)")
        if self.same_estimator:
            return what + ("; the same estimator: the ratio must be 1" if not self.passed else "")
        return what + ("; another estimator: its efficiency is lower" if self.verdict == "WARN" else
                       "; another estimator: reported, not judged")

    def to_json(self) -> dict:
        return {**self.result.to_json(), "same_estimator": self.same_estimator, "verdict": self.verdict,
                "summary": self.summary}
