"""The comparison's check that no side has one batch standing apart from its others (a firefly of 10^4 in one
pixel of one batch moves that batch's image mean far beyond the others' spread, and widens the spread the mean
test divides by as much as it moves the mean). Only a side whose batches were at hand is judged.

Public API::

    check = OutlierCheck.of(test_summary, reference_summary)
    check.passed, check.summary, check.to_json()
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from harness.statistics.constants import OUTLIER_LEVEL
from harness.statistics.outlier_batch import BatchOutlier

if TYPE_CHECKING:
    from harness.comparison.summary import Summary

#: The channels' names, by index, for messages.
CHANNELS = "RGB"


def _fails(outlier: BatchOutlier | None) -> bool:
    return outlier is not None and outlier.p_value < OUTLIER_LEVEL


@dataclass(frozen=True)
class OutlierCheck:
    """Each side's most outlying batch (None where not judged); passes when neither stands apart."""

    test: BatchOutlier | None
    reference: BatchOutlier | None

    @classmethod
    def of(cls, test: Summary, reference: Summary) -> OutlierCheck:
        return cls(test.outlier, reference.outlier)

    @property
    def passed(self) -> bool:
        return not (_fails(self.test) or _fails(self.reference))

    @property
    def summary(self) -> str:
        """One line: the side whose batch stands apart, or what was checked."""
        for side, o in (("test", self.test), ("reference", self.reference)):
            if _fails(o):
                return (f"one {side} batch stands apart (a firefly?): batch {o.batch}'s image mean "
                        f"({CHANNELS[o.channel]}) is {o.value:.6g} where the other {o.batches - 1} average "
                        f"{o.others:.6g}, t = {o.t:.3g} over their spread (p = {o.p_value:.2g}, level {OUTLIER_LEVEL:g})")
        judged = [side for side, o in (("test", self.test), ("reference", self.reference)) if o is not None]
        return (f"no batch stands apart ({' and '.join(judged)})" if judged
                else "outlying batches not judged (no batches at hand, or their image means agree to rounding)")

    def to_json(self) -> dict:
        return {"pass": self.passed, "summary": self.summary, "level": OUTLIER_LEVEL,
                "test": self.test.to_json() if self.test else None,
                "reference": self.reference.to_json() if self.reference else None}
