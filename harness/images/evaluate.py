"""The one place an image case is decided: its renders, given as data, to a CaseVerdict.

`evaluate` takes what the case's renders gave (the tested engine's RenderResult, each reference's Reference, or
the RenderFailure of any of them) and returns the whole verdict: the comparisons, an oracle's overrule (a
closed form's or a scale twin's: harness/images/oracle.py), the notes (a failure's named cause, the budget that
would decide an INCONCLUSIVE case) and PASS, FAIL or INCONCLUSIVE. It renders nothing and reads no file;
whatever it needs of the scene comes in as data. `against_image` does the same for a case judged against a
reference image, `failure` for a case that ends otherwise (its task or its report), and `with_scene_notes` adds
what the run learns of each case's scene.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np

from harness.comparison.cause import named_cause
from harness.comparison.compare import compare_summaries
from harness.comparison.mismatch import diagnose
from harness.comparison.outcome import Comparison
from harness.comparison.strategies import StrategyCheck, compare_strategies
from harness.comparison.summary import Summary, summarize
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import RenderResult
from harness.foreign_text import one_line
from harness.images.case_verdict import CaseVerdict
from harness.images.copy_lines import in_user_terms
from harness.images.oracle import Finding, overrule
from harness.images.references import CLOSED_FORM, Reference
from harness.images.scale_twins import SCALE_TWIN
from harness.images.spp_search import decisive_budget
from harness.images.suite import ImageCase
from harness.integrators import entry


#: On the other cases of a scene whose normals failed: normals see only the camera and the geometry, unless
#: the fault is one that every image shares (a scale applied to every output).
GEOMETRY_NOTE = ("normals failed on this scene: a camera or geometry mismatch, or a fault every image shares "
                 "(its other failures may have that cause)")


@dataclass(frozen=True, kw_only=True)
class RenderFailure:
    """A render of the case that gave no image: one line saying which and why, and what it printed last."""

    reason: str
    output: str = ""


def failure(reason: str, output: str = "") -> CaseVerdict:
    """A FAIL without comparisons: a render, the task or its report ended the case, for `reason` (one line);
    `output`: what a failed render printed last."""
    return CaseVerdict(verdict="FAIL", error=reason, error_output=output)


def render_failure(case: ImageCase, reason: str, output: str = "") -> CaseVerdict:
    """`failure` for a reason an engine gave about `case`, in one line and in the terms of the file the user gave
    (a --scene file's prepared copy is named as that file)."""
    return failure(one_line(in_user_terms(reason, case)), output)


def with_scene_notes(cases: Sequence[ImageCase], verdicts: Sequence[CaseVerdict]) -> list[CaseVerdict]:
    """`verdicts` (of `cases`, in the run's order) with what the run learned of their scenes: once a case that
    checks the geometry (normals) failed on a scene, the scene's later cases carry GEOMETRY_NOTE after their
    own cause, and the failed case carries it where it names no cause of its own. Verdicts do not change."""
    geometry_failed: set[str] = set()
    out = []
    for case, verdict in zip(cases, verdicts, strict=True):
        if case.scene in geometry_failed:
            verdict = replace(verdict, note="; ".join(n for n in (verdict.note, GEOMETRY_NOTE) if n))
        if entry(case.integrator).checks_geometry and verdict.error is None and verdict.failed:
            geometry_failed.add(case.scene)
            verdict = replace(verdict, note=verdict.note or GEOMETRY_NOTE)
        out.append(verdict)
    return out


def _decided(comparisons: dict[str, Comparison], finding: Finding | None, reference_problem: str | None) -> str:
    """FAIL when a deciding comparison failed (or there is none, or the reference image cannot be compared);
    PASS when none failed and one could have shown a defect; else INCONCLUSIVE."""
    deciding = [c for name, c in comparisons.items() if finding is None or name != finding.overruled]
    if reference_problem is not None or not deciding or any(not c.passed for c in deciding):
        return "FAIL"
    return "PASS" if any(c.verdict == "PASS" for c in deciding) else "INCONCLUSIVE"


def _first_failure(tested: RenderResult | RenderFailure | None,
                   references: Mapping[str, Reference | RenderFailure], reference: str) -> RenderFailure | None:
    """The failure the case reports: the reference engine's, the tested engine's, then a closed form's."""
    order = [references.get(reference), tested, *(r for name, r in references.items() if name != reference)]
    return next((r for r in order if isinstance(r, RenderFailure)), None)


def _strategy_check(strategies: Mapping[str, RenderResult | RenderFailure] | None,
                    alpha: float) -> StrategyCheck | None:
    """The tested engine's strategies compared with each other at `alpha` (None: not rendered)."""
    return compare_strategies(strategies, alpha=alpha) if strategies else None


def evaluate(case: ImageCase, tested: RenderResult | RenderFailure | None,
             references: Mapping[str, Reference | RenderFailure], *, alpha: float, reference: str,
             reference_draws_estimator: bool = False, constants: Mapping[str, float] | None = None,
             strategies: Mapping[str, RenderResult | RenderFailure] | None = None,
             strategies_skipped: str = "") -> CaseVerdict:
    """The verdict of `case` from its renders.

    `tested`: the tested engine's batches, or why they failed (None: not rendered, because a render before it
    failed). `references`: by name, the reference engine's (named `reference`) and, where the case has one,
    the closed form's (its `source` is CLOSED_FORM) or the reference engine's render of the scene's scale twin
    (SCALE_TWIN), or why each failed. `alpha`: the level of each
    comparison. `reference_draws_estimator`: the reference engine draws the tested estimator sample for
    sample (the closed form always does), so that its noise is judged too. `constants`: the scene's values a
    factor between the images may be (harness/images/scene_constants.py), for a failure's named cause.
    `strategies`: the tested engine's renders of the integrator's strategies (harness/images/strategy_renders.py),
    or why one failed; compared with each other at `alpha`, any disagreement fails the case.
    `strategies_skipped`: why they were not rendered, for the report."""
    if case.problem:  # a --scene file no engine can be given (what its preparation refused)
        return render_failure(case, case.problem)
    failed = _first_failure(tested, references, reference) or next(
        (r for r in (strategies or {}).values() if isinstance(r, RenderFailure)), None)
    if failed is not None:
        return render_failure(case, failed.reason, failed.output)
    if not isinstance(tested, RenderResult) or reference not in references:
        raise ValueError(f"{case.key}: no failure, and yet no tested render or no {reference} reference")
    refs = {name: r for name, r in references.items() if isinstance(r, Reference)}
    summary = summarize(tested.batches)
    signed = entry(case.integrator).signed
    # The closed form draws the tested estimator unless it knows the mean only; the reference engine does where
    # the caller says so.
    exact_draws = AnalyticEngine.draws_estimator(case.integrator)
    # The reference engine's render of the scene's scale twin draws what it draws.
    same = {name: (r.source == CLOSED_FORM and exact_draws)
            or ((name == reference or r.source == SCALE_TWIN) and reference_draws_estimator)
            for name, r in refs.items()}
    comparisons = {name: compare_summaries(summary, r.summary, alpha, signed=signed, samples=(tested.spp, r.spp),
                                           same_estimator=same[name], heavy_tail=case.heavy_tail)
                   for name, r in refs.items()}
    oracle = next((name for name, r in refs.items() if r.source in (CLOSED_FORM, SCALE_TWIN)), "")
    shown = ("the closed form" if not oracle or refs[oracle].source == CLOSED_FORM
             else f"its own render of the scale twin ({oracle})")
    finding = overrule(comparisons, summary, {name: r.summary for name, r in refs.items()}, alpha, signed,
                       {name: r.spp for name, r in refs.items()}, reference, oracle, shown)
    check = _strategy_check(strategies, alpha)
    verdict = "FAIL" if check is not None and check.disagree else _decided(comparisons, finding, None)
    note, budget = None, ""
    first = next((name for name, c in comparisons.items() if not c.passed), None)
    if verdict == "FAIL" and first is not None:
        note = named_cause(summary, refs[first].summary, signed, dict(constants or {}))
    if verdict == "INCONCLUSIVE":
        ref = refs[reference]
        budget = decisive_budget(summary, tested.spp, ref.summary, ref.spp, alpha, signed, same[reference])
    return CaseVerdict(verdict=verdict, comparisons=comparisons, finding=finding, note=note, decisive_budget=budget,
                       strategies=check, strategies_skipped=strategies_skipped)


def against_image(case: ImageCase, tested: RenderResult, test: Summary, reference: Summary, *, alpha: float,
                  image_samples: int, image: np.ndarray, reference_problem: str | None, convention: str | None = None,
                  constants: Mapping[str, float] | None = None) -> CaseVerdict:
    """The verdict of `case` against a reference image (harness/images/reference_image.py): `test` and
    `reference` are the tested batches and the image as that model summarises them, `image_samples` the
    image's samples per batch, `image` its pixels (for what a failure looks like); `reference_problem`: why
    the image's noise does not fit its model (the case then fails whatever the comparison says);
    `convention`: how the tested image was read to match the image's renderer (a note)."""
    signed = entry(case.integrator).signed
    comparison = compare_summaries(test, reference, alpha, signed=signed, samples=(tested.spp, image_samples))
    # What a failed comparison looks like (|n| for n, a named factor; else a zoom, a shift, a factor, a
    # background): the user's next step.
    note = None if comparison.passed else (
        named_cause(test, reference, signed, dict(constants or {})) or diagnose(tested.mean, image))
    if convention is not None:
        note = "; ".join(n for n in (f"compared as {convention} (the scene is in Nori's dialect)", note) if n)
    comparisons = {"image": comparison}
    return CaseVerdict(verdict=_decided(comparisons, None, reference_problem), comparisons=comparisons, note=note,
                       reference_problem=reference_problem)
