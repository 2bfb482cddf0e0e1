"""Observed false-alarm rates with exact binomial intervals: how a calibration states its figures."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Nominal levels at which every statistical check's false-alarm rate is measured (per test).
CALIBRATION_LEVELS = (0.3, 0.05, 0.01)
#: Confidence of the intervals, simultaneous over every interval of one calibration (Bonferroni).
CALIBRATION_CONFIDENCE = 0.95


@dataclass
class Rate:
    """Rejections among `count` null tests at a nominal level, and the exact interval of the rate."""

    level: float
    count: int
    rejections: int
    low: float
    high: float

    @property
    def observed(self) -> float:
        return self.rejections / self.count if self.count else float("nan")

    @property
    def within(self) -> bool:
        """The nominal level lies inside the interval: the rate is what the check claims."""
        return self.low <= self.level <= self.high

    @property
    def liberal(self) -> bool:
        """The whole interval lies above the nominal level: the check raises more false alarms than it says."""
        return self.low > self.level

    @property
    def verdict(self) -> str:
        """"within", "liberal", or "conservative" (the interval lies below the level: fewer false alarms
        than it says, which costs power but never a false FAIL)."""
        return "within" if self.within else "liberal" if self.liberal else "conservative"

    def to_json(self) -> dict:
        return {"level": self.level, "comparisons": self.count, "rejections": self.rejections,
                "false_alarm_rate": self.observed, "interval": [self.low, self.high], "within": self.within,
                "verdict": self.verdict}


def clopper_pearson(k: int, n: int, confidence: float) -> tuple[float, float]:
    """Exact (Clopper-Pearson) interval of a binomial proportion k/n."""
    if n == 0:
        return 0.0, 1.0
    from scipy import stats as sps  # here: its import costs every harness process most of a second

    ci = sps.binomtest(k, n).proportion_ci(confidence_level=confidence, method="exact")
    return float(ci.low), float(ci.high)


def rates(p_values: np.ndarray, intervals: int, levels: tuple[float, ...] = CALIBRATION_LEVELS,
          confidence: float = CALIBRATION_CONFIDENCE) -> list[Rate]:
    """The rejection rate of null p-values at each level, with intervals simultaneous over `intervals`
    intervals in all (so that a calibrated test has every level inside its interval with `confidence`)."""
    p = np.asarray(p_values, np.float64)
    each = 1.0 - (1.0 - confidence) / max(intervals, 1)
    out = []
    for level in levels:
        k = int(np.count_nonzero(p < level))
        out.append(Rate(level, len(p), k, *clopper_pearson(k, len(p), each)))
    return out


def uniformity_p(p_values: np.ndarray) -> float:
    """Kolmogorov-Smirnov p-value of null p-values against U(0, 1) (a check of the whole distribution)."""
    from scipy import stats as sps

    p = np.asarray(p_values, np.float64)
    return float(sps.kstest(p, "uniform").pvalue) if len(p) else float("nan")
