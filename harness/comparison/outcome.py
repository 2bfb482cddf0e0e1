"""What one comparison found: each scale's tests and the comparison's verdict, with the checks behind it (bad
pixels, independent batches, a batch standing apart, the noise) and why it fails or cannot decide. Made by
harness.comparison.compare."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from harness.comparison.finite import FiniteCheck
from harness.comparison.independence_check import IndependenceCheck
from harness.comparison.outlier_check import OutlierCheck
from harness.comparison.variance_check import VarianceCheck

SCALES = ("pixel", "tile", "image")
@dataclass(kw_only=True)
class ScaleTest:
    """Every test at one scale: how many, at what level, the smallest p-value and where."""

    scale: str
    tests: int
    level: float
    min_p: float
    failures: int
    #: (row, column) of the smallest p-value, in pixels (a tile's top-left corner at the tile scale).
    worst: tuple[int, int]
    #: p-values over the image, min over channels, at pixel resolution.
    p_map: np.ndarray = field(repr=False)

    @property
    def passed(self) -> bool:
        return self.failures == 0

    def to_json(self) -> dict:
        return {"scale": self.scale, "tests": self.tests, "level": self.level, "min_p": self.min_p,
                "failures": self.failures, "worst": list(self.worst), "pass": self.passed}


@dataclass(kw_only=True)
class Comparison:
    """The verdict of one test-vs-reference comparison."""

    scales: list[ScaleTest]
    #: The error metrics (relMSE, FLIP, ...); empty where the comparison was made without them.
    metrics: dict[str, float]
    #: Relative bias b of the image mean (the test image scaled by 1 + b) that the image scale detects half
    #: of the time (in at least one channel), at this comparison's noise and level.
    detectable_bias: float
    batches: tuple[int, int]
    #: NaN, Inf and (unless signed) negative pixels of either side; any fails the comparison.
    finite: FiniteCheck
    #: The same for one 8x8 tile alone (the tile's values scaled by 1 + b, relative to its own mean), detected
    #: half of the time by the tile scale: the median over tiles with a non-zero mean (inf if there are none).
    detectable_tile_bias: float = float("inf")
    #: The same found POWER_TARGET (90 %) of the time: what `--detect-bias` budgets for.
    detectable_bias_most: float = float("nan")
    #: The FLIP map (H, W) the metrics were taken from, for the report's picture; None without metrics.
    flip_map: np.ndarray | None = field(default=None, repr=False, compare=False)
    #: Whether each side's batches are independent, without which the scales' tests mean nothing.
    independence: IndependenceCheck | None = None
    #: The test's per-sample variance against the reference's; None where the sample counts are unknown.
    variance: VarianceCheck | None = None
    #: Whether a batch of either side stands apart from the others (a firefly); None where not made.
    outliers: OutlierCheck | None = None
    #: Why nothing failed and yet nothing was shown (one line; "" when the comparison decides): both images one
    #: value everywhere, or a detectable bias of the image mean above INCONCLUSIVE_BIAS.
    inconclusive: str = ""

    @property
    def verdict(self) -> str:
        """"FAIL" when a check fails, else "INCONCLUSIVE" when the comparison could not have shown a defect,
        else "PASS"."""
        return "FAIL" if not self.passed else "INCONCLUSIVE" if self.inconclusive else "PASS"

    @property
    def passed(self) -> bool:
        return (self.trusted and all(s.passed for s in self.scales)
                and (self.variance is None or self.variance.passed))

    @property
    def independent(self) -> bool:
        """No side's batches were found dependent (or none could be judged)."""
        return self.independence is None or self.independence.passed

    @property
    def no_outlier(self) -> bool:
        """No side has a batch that stands apart from its others (or none could be judged)."""
        return self.outliers is None or self.outliers.passed

    @property
    def trusted(self) -> bool:
        """The inputs the scales' tests assume: every pixel finite, independent batches, none standing apart."""
        return self.finite.passed and self.independent and self.no_outlier

    @property
    def failed_scales(self) -> list[str]:
        return [s.scale for s in self.scales if not s.passed]

    @property
    def failed_checks(self) -> list[str]:
        """"finite", "independent" and "outlier" (if they failed), the failed scales, then "variance" (if it
        failed)."""
        noise = self.variance is None or self.variance.passed
        return (([] if self.finite.passed else ["finite"]) + ([] if self.independent else ["independent"])
                + ([] if self.no_outlier else ["outlier"]) + self.failed_scales + ([] if noise else ["variance"]))

    @property
    def reason(self) -> str:
        """Why it failed, one line: bad pixels (NaN, Inf, negative), dependent or outlying batches, a noise
        beyond the reference's (a firefly), then the scales that reject; "" when it passed."""
        parts = [] if self.finite.passed else [self.finite.summary]
        if not self.independent:
            parts.append(self.independence.summary)
        if not self.no_outlier:
            parts.append(self.outliers.summary)
        if self.variance is not None and not self.variance.passed:
            parts.append(self.variance.summary)
        if self.failed_scales:
            parts.append(f"{', '.join(self.failed_scales)} scale(s) reject")
        return "; ".join(parts)

    def to_json(self) -> dict:
        return {"pass": self.passed, "verdict": self.verdict, "inconclusive": self.inconclusive or None,
                "finite": self.finite.to_json(),
                "independence": self.independence.to_json() if self.independence else None,
                "variance": self.variance.to_json() if self.variance else None,
                "outliers": self.outliers.to_json() if self.outliers else None,
                "tests": [s.to_json() for s in self.scales],
                "metrics": self.metrics, "detectable_bias": self.detectable_bias,
                "detectable_bias_90": self.detectable_bias_most,
                "detectable_tile_bias": self.detectable_tile_bias, "batches": list(self.batches)}
