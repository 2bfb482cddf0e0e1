"""One check's verdict: PASS, WARN (passed, with warnings), FAIL, SKIP; statistical checks decided later, at the
run's level; a check that could not judge its input fails."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from harness.warps.findings import Finding


@dataclass
class CheckResult:
    """One check's verdict, its headline figure and the numbers behind it.

    passed is None for a check that was skipped, and for a statistical check
    whose p-value has not been compared with the run's level yet. A check that
    passed with WARN findings (see warp_findings) has the verdict WARN. A check
    that could not judge its input (`not_judged`: no sample reached its histogram,
    a pdf that expects too few samples to test) fails, with a NaN p-value.
    """

    passed: bool | None
    figure: float | None
    summary: str
    details: dict[str, Any] = field(default_factory=dict)
    p_value: float | None = None
    #: A failure that no significance level can excuse (samples outside the domain, NaN, ...).
    hard_failure: str | None = None
    skipped: bool = False
    #: What the check found at individual samples, most serious first (failures, then warnings).
    findings: list[Finding] = field(default_factory=list)
    #: Why the check could not judge its input; such a check fails.
    not_judged: str | None = None

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "WARN"]

    @property
    def verdict(self) -> str | None:
        """"PASS", "WARN" (passed, with warnings), "FAIL", "SKIP", or None while undecided."""
        if self.skipped:
            return "SKIP"
        if self.passed is None:
            return None
        return "FAIL" if not self.passed else "WARN" if self.warnings else "PASS"

    def decide(self, level: float) -> None:
        """Set `passed` for a statistical check from its p-value and the per-test level."""
        if self.p_value is not None:
            self.passed = self.hard_failure is None and self.not_judged is None and self.p_value >= level
            self.details["level"] = level

    def to_json(self) -> dict[str, Any]:
        out = {"pass": self.passed, "verdict": self.verdict, "figure": self.figure, "summary": self.summary}
        if self.p_value is not None:
            out["p_value"] = self.p_value
        if self.hard_failure:
            out["hard_failure"] = self.hard_failure
        if self.not_judged:
            out["not_judged"] = self.not_judged
        if self.skipped:
            out["skipped"] = True
        if self.findings:
            out["findings"] = [f.to_json() for f in self.findings]
        out.update(self.details)
        return out


def skipped(reason: str) -> CheckResult:
    return CheckResult(None, None, f"skipped: {reason}", skipped=True)


def not_judged(reason: str, statistical: bool = True, **details: Any) -> CheckResult:
    """A check that could not judge its input: it fails, saying why. A statistical one keeps a (NaN) p-value, so
    that the run's Sidak level counts it whatever its input was."""
    return CheckResult(False, float("nan"), f"not judged: {reason}", details=details,
                       p_value=float("nan") if statistical else None, not_judged=reason)
