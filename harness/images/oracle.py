"""An oracle between the tested engine and the reference engine: the closed form, or where a case has none the
reference engine's own render of the scene's scale twin (harness/images/scale_twins.py).

Where the tested render agrees with the oracle but not with the reference engine's, the disagreement is the
reference's: its comparison is overruled (harness/images/evaluate.py then leaves it out of the verdict), with a
finding that says what the reference breaks and the evidence (the reference's own comparison with the oracle,
and each engine's image-mean ratio to it). Where the tested render disagrees with the oracle, nothing is
overruled.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.comparison.compare import Comparison, compare_summaries
from harness.comparison.summary import Summary


@dataclass(kw_only=True)
class Finding:
    """A reference overruled by the closed form, and why."""

    overruled: str                 # the reference engine whose failed comparison no longer decides
    text: str                      # one line for the terminal and results.json
    reference_vs_closed_form: dict  # the reference's own comparison with the oracle (Comparison.to_json)
    mean_ratio: dict[str, list[float]]  # image mean over the closed form's, per channel: the reference's, "tested"

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


def overrule(comparisons: dict[str, Comparison], tested: Summary, references: dict[str, Summary],
             alpha: float, signed: bool, samples: dict[str, int], reference: str,
             oracle: str, shown_oracle: str = "the closed form") -> Finding | None:
    """A finding when the tested render agrees with the oracle and fails against the reference engine; else
    None.

    `comparisons`, `references` (summaries) and `samples` (samples per pixel) are keyed by engine name, the
    reference engine's `reference` and the oracle's `oracle` (`shown_oracle` in the finding's words)."""
    exact, other = comparisons.get(oracle), comparisons.get(reference)
    if exact is None or other is None or not exact.passed or other.passed:
        return None
    noise = "variance" in other.failed_checks or (other.independence is not None and not other.independence.test.passed)
    if noise and exact.variance is not None and not exact.variance.same_estimator:
        return None  # a closed form that does not draw the tested estimator knows the mean, not its noise
    evidence = compare_summaries(references[reference], references[oracle], alpha, signed=signed,
                                 samples=(samples[reference], samples[oracle]),
                                 same_estimator=exact.variance is None or exact.variance.same_estimator)
    ratios = {reference: _ratio(references[reference], references[oracle]),
              "tested": _ratio(tested, references[oracle])}
    shown = reference.capitalize()
    if evidence.passed:
        what = f"disagrees with the tested engine, though {shown_oracle} does not reject either"
    else:
        what = f"breaks {shown_oracle}: {shown} against it {_where(evidence)}"
    text = (f"reference {what}; image mean over {shown_oracle}: {shown} {_fmt(ratios[reference])}, tested "
            f"{_fmt(ratios['tested'])} (the tested engine agrees with {shown_oracle}; against {shown} it "
            f"{_where(other)})")
    return Finding(overruled=reference, text=text, reference_vs_closed_form=evidence.to_json(), mean_ratio=ratios)
