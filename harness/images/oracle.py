"""The closed form as the oracle between our renderer and Mitsuba.

Where a scene has a closed form and our render agrees with it but not with Mitsuba, the disagreement is
Mitsuba's: the case passes, with a finding that says what the reference breaks and the evidence (Mitsuba's
own comparison with the closed form, and each engine's image-mean ratio to it). Where ours disagrees with
the closed form, nothing is overruled and the case fails as before.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.comparison.compare import Comparison, compare_summaries
from harness.comparison.summary import Summary


@dataclass
class Finding:
    """A reference overruled by the closed form, and why."""

    overruled: str                 # the reference engine whose failed comparison no longer decides
    text: str                      # one line for the terminal and results.json
    reference_vs_closed_form: dict  # the reference's own comparison with the closed form (Comparison.to_json)
    mean_ratio: dict[str, list[float]]  # image mean over the closed form's, per channel, by engine

    def to_json(self) -> dict:
        return {"overruled": self.overruled, "text": self.text, "mean_ratio": self.mean_ratio,
                "reference_vs_closed_form": self.reference_vs_closed_form}


def _ratio(test: Summary, exact: Summary) -> list[float]:
    with np.errstate(divide="ignore", invalid="ignore"):
        return [float(x) for x in np.asarray(test.image.mean) / np.asarray(exact.image.mean)]


def _where(c: Comparison) -> str:
    failed = [s for s in c.scales if not s.passed]
    untrusted = (("" if c.finite.passed else "; non-finite pixels")
                 + ("" if c.independent else "; batches not independent")
                 + ("" if c.variance is None or c.variance.passed else f"; {c.variance.summary}"))
    if not failed:
        return "passes" if not untrusted else "fails: " + untrusted[2:]
    worst = min(failed, key=lambda s: s.min_p)
    return (f"fails at {', '.join(s.scale for s in failed)} scale (worst at row {worst.worst[0]}, column "
            f"{worst.worst[1]}, p = {worst.min_p:.2g})" + untrusted)


def _fmt(ratio: list[float]) -> str:
    return "/".join(f"{r:.4f}" for r in ratio)


def decide(comparisons: dict[str, Comparison], ours: Summary, references: dict[str, Summary],
           alpha: float, signed: bool, samples: dict[str, int], reference: str, closed_form: str) -> Finding | None:
    """A finding when ours agrees with the closed form and fails against the reference engine; else None.

    `comparisons`, `references` (summaries) and `samples` (samples per pixel) are keyed by engine name, the
    reference engine's `reference` and the closed form's `closed_form`."""
    exact, other = comparisons.get(closed_form), comparisons.get(reference)
    if exact is None or other is None or not exact.passed or other.passed:
        return None
    noise = "variance" in other.failed_checks or (other.independence is not None and not other.independence.test.passed)
    if noise and exact.variance is not None and not exact.variance.same_estimator:
        return None  # a closed form that does not draw our estimator knows the mean, not our noise
    evidence = compare_summaries(references[reference], references[closed_form], alpha, signed=signed,
                                 samples=(samples[reference], samples[closed_form]),
                                 same_estimator=exact.variance is None or exact.variance.same_estimator)
    ratios = {reference: _ratio(references[reference], references[closed_form]),
              "ours": _ratio(ours, references[closed_form])}
    shown = reference.capitalize()
    if evidence.passed:
        what = "disagrees with ours, though the closed form does not reject either"
    else:
        what = f"breaks the closed form: {shown} against it {_where(evidence)}"
    text = (f"reference {what}; image mean over the closed form: {shown} {_fmt(ratios[reference])}, ours "
            f"{_fmt(ratios['ours'])} (ours agrees with the closed form; ours against {shown} {_where(other)})")
    return Finding(reference, text, evidence.to_json(), ratios)
