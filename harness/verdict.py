"""A run's verdict from what its suites judged.

An item (an image case, an invariance cell, a warp) is judged when it ends in PASS or FAIL; one that was
skipped (not applicable, not run) or inconclusive (no signal to judge) is not. A run PASSes only when nothing
failed and each of its suites judged something; a run with a suite that judged nothing is NOTHING_JUDGED,
never a PASS, and says why. `harness/cli.py` maps each verdict to the exit status.

Public API::

    tally = Tally("image cases", passed=3, failed=0, not_judged=("2 not applicable: no point light",))
    verdict, reason = run_verdict([tally, ...])
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


class Verdict(Enum):
    PASS = "PASS"
    FAIL = "FAIL"
    #: Nothing was judged: no item ran, or every one was skipped or inconclusive.
    NOTHING_JUDGED = "NOTHING JUDGED"


@dataclass(frozen=True)
class Tally:
    """What one suite of a run judged: items that passed and failed, and why others were not judged."""

    #: What the items are, plural ("image cases", "invariance cells of mcval").
    what: str
    passed: int = 0
    failed: int = 0
    #: One line per reason items were not judged ("3 inconclusive: the base render is constant (all 0)"), or,
    #: when there were no items at all, why not.
    not_judged: tuple[str, ...] = ()

    @property
    def judged(self) -> int:
        return self.passed + self.failed

    def why_nothing(self) -> str:
        """Why this suite judged nothing (meaningful when `judged` is 0)."""
        return f"{self.what}: {'; '.join(self.not_judged)}" if self.not_judged else f"no {self.what} ran"

    def to_json(self) -> dict:
        return {"what": self.what, "passed": self.passed, "failed": self.failed, "not_judged": list(self.not_judged)}


def run_verdict(tallies: list[Tally], ok: bool = True) -> tuple[Verdict, str]:
    """The run's verdict and, for NOTHING_JUDGED, one line saying why. `ok` False: something failed outside
    the tallied items (a warp library that lacks a pdf), which is a FAIL however much was judged."""
    if not ok or any(t.failed for t in tallies):
        return Verdict.FAIL, ""
    empty = [t for t in tallies if not t.judged]
    if empty or not tallies:
        why = "; ".join(t.why_nothing() for t in empty) or "no suite ran"
        return Verdict.NOTHING_JUDGED, f"nothing was judged: {why}"
    return Verdict.PASS, ""
