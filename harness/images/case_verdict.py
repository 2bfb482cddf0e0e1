"""What one image case was judged to be: its comparisons, a closed form's overrule, its notes and its verdict.
Made only by harness/images/evaluate.py; an ImageResult reads it."""
from __future__ import annotations

from dataclasses import dataclass, field

from harness.comparison.outcome import Comparison
from harness.comparison.strategies import StrategyCheck
from harness.foreign_text import foreign
from harness.images.oracle import Finding

#: The verdicts of a case.
VERDICTS = ("PASS", "FAIL", "INCONCLUSIVE")


@dataclass(frozen=True, kw_only=True)
class CaseVerdict:
    """The verdict of one (scene, integrator) and everything it rests on.

    `error` (one line) says why a render failed (crashed, killed, timed out, reported an error); the case then
    fails without comparisons. `finding` is set when the closed form overrules a reference
    (harness/images/oracle.py): that reference's failed comparison then does not decide.
    """

    verdict: str
    #: The tested render against each reference, by the reference's name (the reference engine's first).
    comparisons: dict[str, Comparison] = field(default_factory=dict)
    finding: Finding | None = None
    error: str | None = None
    #: The last lines (up to 50) a failed render printed, where it printed any.
    error_output: str = ""
    #: The named cause of a failure (a factor, |n|, a zoom), and the scene's notes (its normals failed).
    note: str | None = None
    #: Against a reference image: why it cannot be compared under its noise model (the case then fails).
    reference_problem: str | None = None
    #: For an INCONCLUSIVE case: the samples per pixel that would decide it, or why none would (one line).
    decisive_budget: str = ""
    #: The tested engine's strategies of the integrator against each other (harness/comparison/strategies.py):
    #: any disagreement fails the case; None where they were not compared, `strategies_skipped` saying why.
    strategies: StrategyCheck | None = None
    strategies_skipped: str = ""

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise ValueError(f"a case's verdict is one of {', '.join(VERDICTS)}, not {self.verdict!r}")
        # Why a render failed is often an engine's own text (Mitsuba's message quoting a scene's 1 MB tag
        # name, a renderer's output): bounded here, whichever engine and stage it came from.
        if self.error is not None:
            object.__setattr__(self, "error", foreign(self.error))
        object.__setattr__(self, "error_output", foreign(self.error_output, keep="tail"))

    @property
    def deciding(self) -> dict[str, Comparison]:
        """The comparisons the verdict rests on: all but one the closed form overruled."""
        overruled = self.finding.overruled if self.finding else None
        return {name: c for name, c in self.comparisons.items() if name != overruled}

    @property
    def passed(self) -> bool:
        return self.verdict == "PASS"

    @property
    def failed(self) -> bool:
        return self.verdict == "FAIL"

    @property
    def failures(self) -> str:
        """Each failed comparison's reason, then the strategy check's where the strategies disagree, one line
        ("against mitsuba: ...; against analytic: ...; strategies DIFFERS: ems differs from ...")."""
        failed = [f"against {n}: {c.reason}" for n, c in self.comparisons.items() if not c.passed]
        if self.strategies is not None and self.strategies.disagree:
            failed.append(f"strategies {self.strategies.verdict}: {self.strategies.reason}")
        return "; ".join(failed)

    @property
    def why(self) -> str:
        """Why the case failed, cause first: the render's error, the named cause (a factor, |n|), the reference
        image's misfit, then the failed comparisons; "" when it did not fail."""
        if not self.failed:
            return ""
        return "; ".join(x for x in (self.error, self.note, self.reference_problem,
                                     None if self.error else self.failures) if x)

    @property
    def inconclusive(self) -> str:
        """Why the case is INCONCLUSIVE, with what would decide it ("" when it is not)."""
        if self.verdict != "INCONCLUSIVE":
            return ""
        why = next(c.inconclusive for c in self.deciding.values() if c.inconclusive)
        return why + (f"; {self.decisive_budget}" if self.decisive_budget else "")
