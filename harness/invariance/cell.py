"""What the invariance check decides: a case, each variant against the base, and a cell (one engine x
invariance x case) with its status: pass, fail, float32 (broke where float32 cannot represent the scene: a
limit, not a failure) or inconclusive (the base has no signal: not judged)."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from harness.comparison.compare import Comparison
from harness.invariance.signal import BaseSignal
from harness.invariance.variants import Variant

#: A cell's statuses that are verdicts; "inconclusive" is not one.
JUDGED = ("pass", "fail", "float32")


@dataclass(frozen=True)
class InvarianceCase:
    """One scene with one integrator, at the check's resolution and samples."""

    scene: Path
    integrator: str
    spp: int
    res: int
    #: Why the scene cannot be rendered at all (a --scene Nori file without a translation), or "".
    problem: str = ""

    @property
    def key(self) -> str:
        return f"{self.scene.stem}:{self.integrator}"


@dataclass
class VariantResult:
    """One variant against the base: the comparison, the image-mean ratio (mapped back over base), why
    float32 cannot represent the variant's scene, if it cannot, and why its batches are not independent
    (all one image where the base's vary), if they are not."""

    variant: Variant
    comparison: Comparison | None
    ratio: float
    error: str | None = None
    float32_limit: str | None = None
    dependence: str | None = None

    @property
    def passed(self) -> bool:
        return (self.error is None and self.dependence is None and self.comparison is not None
                and self.comparison.passed)

    @property
    def status(self) -> str:
        """"pass"; "float32" (it broke, on a scene float32 cannot represent: a limit, not a failure); "fail"."""
        return "pass" if self.passed else "float32" if self.float32_limit else "fail"

    def to_json(self) -> dict:
        c = self.comparison
        return {"variant": self.variant.label, "pass": self.passed, "status": self.status, "ratio": self.ratio,
                "error": self.error, "float32_limit": self.float32_limit, "dependence": self.dependence,
                "failed_checks": c.failed_checks if c else [], "min_p": {s.scale: s.min_p for s in c.scales} if c
                else {}, "detectable_bias": c.detectable_bias if c else None}


@dataclass
class Cell:
    """One engine x invariance x case: every variant of the invariance against the base render."""

    engine: str
    invariance: str
    case: InvarianceCase
    variants: list[VariantResult] = field(default_factory=list)
    #: Why there is no base image (its render failed), or None.
    base_error: str | None = None
    #: What the base render shows (None where it was not rendered).
    base: BaseSignal | None = None
    #: Why the base's batches are not independent (one image where noise is expected), or None.
    dependence: str | None = None

    @property
    def failing(self) -> list[VariantResult]:
        return [v for v in self.variants if v.status == "fail"]

    @property
    def beyond_float32(self) -> list[VariantResult]:
        return [v for v in self.variants if v.status == "float32"]

    @property
    def not_judged(self) -> str | None:
        """Why the cell is inconclusive (its base has no signal and nothing failed), or None."""
        failed = self.base_error or self.dependence or self.failing
        return None if failed or self.base is None else self.base.no_signal

    @property
    def status(self) -> str:
        """"fail" (no base, batches not independent, or a failing variant), "inconclusive" (not_judged),
        "float32" (only variants beyond float32 broke) or "pass"."""
        if self.base_error or self.dependence or self.failing:
            return "fail"
        return "inconclusive" if self.not_judged else "float32" if self.beyond_float32 else "pass"

    @property
    def passed(self) -> bool:
        """Judged and not failed (a variant beyond float32 is not a failure); an inconclusive cell is not."""
        return self.status in ("pass", "float32")

    @property
    def judged(self) -> bool:
        return self.status in JUDGED

    @property
    def worst_ratio(self) -> float:
        """The ratio furthest from 1 (NaN if none was measured)."""
        ratios = [v.ratio for v in self.variants if np.isfinite(v.ratio)]
        return max(ratios, key=lambda r: abs(r - 1.0)) if ratios else float("nan")

    def to_json(self) -> dict:
        return {"engine": self.engine, "invariance": self.invariance, "scene": self.case.scene.stem,
                "integrator": self.case.integrator, "pass": self.passed, "status": self.status,
                "ratio": self.worst_ratio, "failing": [v.variant.label for v in self.failing],
                "beyond_float32": [v.variant.label for v in self.beyond_float32], "base_error": self.base_error,
                "dependence": self.dependence, "not_judged": self.not_judged,
                "base": self.base.to_json() if self.base else None,
                "variants": [v.to_json() for v in self.variants], "spp": self.case.spp, "res": self.case.res}
