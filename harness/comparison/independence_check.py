"""The comparison's check that each side's batches are independent, before its mean test is trusted.

A side fails it in two ways: a pair of its batches agrees far beyond chance
(`harness.statistics.independence`), or, for the test side against a reference that draws the same
estimator (`same_estimator`), all its batches are alike while the reference's vary at ALIKE_MIN_FRACTION
of the elements or more (a renderer that ignores the seed it is given: the spread the mean test divides
by is zero): unless its image is one value everywhere, which is no signal, not a seed ignored. Without the
same estimator, batches all alike may be an estimator without noise (mcval on a
lone plane under ambient occlusion, against Mitsuba's emitter sampling), so they are not judged. Only a
side whose batches were at hand is judged (a stored reference keeps no batches; it was judged when it
was made).

Public API::

    check = IndependenceCheck.of(test_summary, reference_summary, same_estimator)
    check.passed, check.summary, check.to_json()
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from harness.statistics.independence import BatchDependence
from harness.statistics.welch import beyond_rounding

if TYPE_CHECKING:
    from harness.comparison.summary import Summary

#: All batches alike on one side are dependent when the other side varies at this fraction of the elements
#: (pixel and channel) or more, and at ALIKE_MIN_ELEMENTS at least.
ALIKE_MIN_FRACTION = 0.01
ALIKE_MIN_ELEMENTS = 16
#: A side that is one value everywhere is not accused of ignoring its seed while the other side varies at fewer
#: than this fraction of the elements: its batches may all have missed what is there (no signal). Beside noise
#: over most of the frame, no batch could have missed it all.
CONSTANT_MISSED_FRACTION = 0.25


def constant_image(summary: Summary) -> bool:
    """Every pixel of every batch the same value (an image with no signal: nothing in view, or a flat field)."""
    mean = np.asarray(summary.pixel.mean)
    return bool(mean.size and np.isfinite(mean).all() and np.ptp(mean) == 0
                and not np.any(np.asarray(summary.pixel.var_of_mean)))


def varying_elements(summary: Summary) -> int:
    """Pixel elements whose batches differ beyond float rounding (as batch_dependence counts them)."""
    return int(np.count_nonzero(beyond_rounding(summary.pixel)))


@dataclass(frozen=True)
class SideIndependence:
    """One side's evidence and verdict."""

    #: None when the side's batches were not at hand (a stored summary) or are too few (K < 3).
    evidence: BatchDependence | None
    #: Elements where the other side's batches vary; of all elements.
    other_varying: int
    elements: int
    #: Whether batches all alike are judged: the other side draws the same estimator.
    judge_alike: bool = False
    #: Whether the side's image is one value everywhere in every batch: batches that agree because nothing is
    #: in view are no evidence against the seed (the comparison calls it no signal instead).
    constant: bool = False

    @property
    def alike(self) -> bool:
        """Every batch the same image, not a constant one, while the other side's, drawing the same estimator,
        vary widely."""
        return (self.judge_alike and self.evidence is not None and self.evidence.varying == 0
                and not self.no_signal
                and self.other_varying >= max(ALIKE_MIN_ELEMENTS, ALIKE_MIN_FRACTION * self.elements))

    @property
    def no_signal(self) -> bool:
        """Batches all alike because the image is one value everywhere, beside another side whose noise is
        confined to a part of the frame (a small object that every batch of this side may have missed)."""
        return self.constant and self.other_varying < CONSTANT_MISSED_FRACTION * self.elements

    @property
    def passed(self) -> bool:
        return self.evidence is None or not (self.alike or self.evidence.dependent)

    def reason(self, side: str, other: str) -> str:
        """One line on why this side failed ("" when it did not)."""
        e = self.evidence
        if e is None or self.passed:
            return ""
        if self.alike:
            return (f"batches not independent: all {e.batches} {side} batches are the same image, where the "
                    f"{other}'s vary at {self.other_varying} pixel values (is the seed it is given used?)")
        return (f"batches not independent: {side} batches {e.pair[0]} and {e.pair[1]} have residual correlation "
                f"{e.correlation:.2f} (independent batches: {e.independent_correlation:.2f}; p = {e.p_value:.1g})")

    def to_json(self) -> dict | None:
        if self.evidence is None:
            return None
        return {**self.evidence.to_json(), "alike": self.alike, "other_varying": self.other_varying,
                "pass": self.passed}


@dataclass(frozen=True)
class IndependenceCheck:
    """Both sides' independence; passes when neither side fails."""

    test: SideIndependence
    reference: SideIndependence

    @classmethod
    def of(cls, test: Summary, reference: Summary, same_estimator: bool = False) -> IndependenceCheck:
        """`same_estimator`: the reference draws the test's estimator, sample for sample."""
        elements = int(test.pixel.mean.size)
        return cls(SideIndependence(test.dependence, varying_elements(reference), elements, same_estimator,
                                    constant_image(test)),
                   SideIndependence(reference.dependence, varying_elements(test), elements))

    @property
    def passed(self) -> bool:
        return self.test.passed and self.reference.passed

    @property
    def summary(self) -> str:
        """One line: the failing sides' reasons, or what was checked."""
        reasons = [r for r in (self.test.reason("test", "reference"), self.reference.reason("reference", "test"))
                   if r]
        if reasons:
            return "; ".join(reasons)
        judged = [name for name, s in (("test", self.test), ("reference", self.reference)) if s.evidence]
        if self.test.no_signal and self.test.evidence is not None and self.test.evidence.varying == 0:
            return ("no signal: the test's batches agree because its image is one value everywhere (nothing to "
                    "judge their independence by)")
        return (f"batches independent ({' and '.join(judged)})" if judged
                else "batch independence not judged (no batches at hand)")

    def to_json(self) -> dict:
        return {"pass": self.passed, "summary": self.summary, "test": self.test.to_json(),
                "reference": self.reference.to_json()}
