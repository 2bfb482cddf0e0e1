"""Running the image suite: our renders against Mitsuba (and closed forms), with layered verdicts."""
from __future__ import annotations

import zlib
from dataclasses import dataclass
from functools import cached_property
from typing import Callable

import numpy as np

from harness.comparison.compare import Comparison, compare_summaries, summarize
from harness.images.oracle import Finding, decide
from harness.engines.analytic import AnalyticEngine
from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.base import Engine, RenderFailed, RenderResult
from harness.images.suite import OUR_SPP, ImageCase
from harness.images.references import CLOSED_FORM, RESOLUTION, Reference, load_reference, render_reference
from harness.statistics.constants import IMAGE_BATCHES, SIGNIFICANCE, sidak_level
from harness.integrators import entry

GEOMETRY_NOTE = "camera or geometry mismatch (normals failed on this scene)"


@dataclass
class ImageResult:
    """One (scene, integrator): our batches against each reference, and the verdicts.

    `error` (one line) says why a render failed (crashed, killed, timed out, reported an error); the case
    then fails without comparisons, and `ours` is None if our render was the one that failed. `finding` is
    set when the closed form overrules a reference (harness/images/oracle.py): that reference's failed
    comparison then does not fail the case.
    """

    case: ImageCase
    ours: RenderResult | None
    references: dict[str, Reference]
    comparisons: dict[str, Comparison]
    reference_source: str
    seed: int
    note: str | None = None
    alpha: float = SIGNIFICANCE
    run_seed: int = 0
    error: str | None = None
    finding: Finding | None = None
    tested: str = ""  # the tested engine's name, for a result without our render

    @property
    def passed(self) -> bool:
        overruled = self.finding.overruled if self.finding else None
        return self.error is None and all(c.passed for name, c in self.comparisons.items() if name != overruled)

    def to_json(self) -> dict:
        if self.error is not None or self.ours is None:
            seconds = {k: r.seconds for k, r in self.references.items()}
            return {"integrator": self.case.integrator, "scene": self.case.scene, "engine": self.engine,
                    "pass": False, "error": self.error, "tests": {}, "metrics": {},
                    "seconds": {**({self.engine: self.ours.seconds} if self.ours else {}), **seconds},
                    "reference": self.reference_source, "note": self.note, "seed": self.seed, "alpha": self.alpha,
                    "idiff": self.idiff}
        first = self.comparisons[next(iter(self.comparisons))]  # the reference engine's (the closed form's after it)
        batch_means = self.ours.batch_means
        tested = self.engine
        return {
            "integrator": self.case.integrator, "scene": self.case.scene, "engine": tested, "pass": self.passed,
            "tests": {name: c.to_json() for name, c in self.comparisons.items()},
            "metrics": first.metrics,
            "seconds": {tested: self.ours.seconds, **{k: r.seconds for k, r in self.references.items()}},
            "reference": self.reference_source, "note": self.note, "error": None, "seed": self.seed,
            "alpha": self.alpha, "spp": {tested: self.ours.spp, **{k: r.spp for k, r in self.references.items()}},
            "batches": {tested: self.ours.count, **{k: r.summary.image.k for k, r in self.references.items()}},
            "image_mean": batch_means.mean(axis=0).tolist(),
            "image_mean_se": (batch_means.std(axis=0, ddof=1) / np.sqrt(len(batch_means))).tolist(),
            "idiff": self.idiff, "finding": self.finding.to_json() if self.finding else None,
        }

    @property
    def engine(self) -> str:
        """The tested engine's name (the key of its figures in results.json)."""
        return self.ours.engine if self.ours is not None else self.tested

    @cached_property
    def idiff(self) -> dict:
        """What idiff, at OpenImageIO's test-suite thresholds, says of our mean image against the
        reference's mean (the reference engine's, else the closed form's); verdict "n/a" with a reason when
        there is no pair of images to compare."""
        ref = next(iter(self.references.values()), None)
        if self.error is not None or self.ours is None or ref is None:
            return {"verdict": "n/a", "reason": self.error or "no reference image"}
        from harness.comparison.idiff import idiff
        try:
            return idiff(self.ours.mean, ref.summary.mean_image)
        except Exception as e:  # a side report never breaks the run
            return {"verdict": "n/a", "reason": f"idiff failed: {e}"}


def case_seed(case: ImageCase, seed: int) -> int:
    """Distinct seeds per case, so two integrators on one scene do not share their noise."""
    return (zlib.crc32(case.key.encode()) + 7919 * seed) % 2**31


def _reason(e: Exception) -> str:
    """One line saying why a render failed."""
    if isinstance(e, RenderFailed):
        return e.reason
    text = str(e).strip().splitlines()
    return f"{type(e).__name__}: {text[0]}" if text else type(e).__name__


def closed_forms(cases: list[ImageCase]) -> dict[ImageCase, bool]:
    """Per case, whether the analytic engine has its closed form (then a second reference)."""
    params = {"res": str(RESOLUTION)}
    return {c: AnalyticEngine.supports(str(c.path), params, c.integrator) for c in cases}


def comparison_level(cases: list[ImageCase], has_closed_form: dict[ImageCase, bool]) -> float:
    """The per-comparison level of a run of `cases`: its Sidak share of the family-wise SIGNIFICANCE."""
    return sidak_level(SIGNIFICANCE, len(cases) + sum(has_closed_form.values()))


def run_images(cases: list[ImageCase], ours: Engine, reference: Engine, seed: int = 0,
               on_status: Callable[[Status], None] | None = None,
               on_message: Callable[[str], None] | None = None,
               executor: Executor | None = None) -> tuple[list[ImageResult], float]:
    """Every case, one task each on `executor` (default: here, one after another); all comparisons of the
    run share a family-wise false-alarm rate of SIGNIFICANCE (Sidak). Returns the results, in the order of
    `cases`, and the per-comparison alpha. A render that fails (our RenderFailed, or any exception of a
    reference engine), or a task whose worker dies, fails its case with the reason, and the run goes on."""
    from harness.images.case_task import CaseJob, run_case_job, share_scene_bundles

    executor = executor or SerialExecutor()
    has_closed_form = closed_forms(cases)
    alpha = comparison_level(cases, has_closed_form)
    bundles = share_scene_bundles(executor, cases, (ours, reference))
    tasks = [Task(case.key, run_case_job,
                  (CaseJob(case, case_seed(case, seed), alpha, seed, has_closed_form[case], ours, reference),
                   bundles.get(case.scene)))
             for case in cases]
    outcomes = executor.run(tasks, on_status)
    geometry_failed: set[str] = set()
    results = []
    for case, outcome in zip(cases, outcomes):
        if outcome.ok:
            result, messages = outcome.value
        else:
            result, messages = ImageResult(case, None, {}, {}, "none", case_seed(case, seed), None, alpha, seed,
                                           f"task failed: {outcome.error}", tested=ours.name), []
        for m in messages:
            if on_message:
                on_message(m)
        if case.scene in geometry_failed:
            result.note = GEOMETRY_NOTE
        if entry(case.integrator).checks_geometry and result.error is None and not result.passed:
            geometry_failed.add(case.scene)
            result.note = GEOMETRY_NOTE
        if result.error is not None and on_message:
            on_message(f"{case.key}: {result.error}")
        if result.finding is not None and on_message:
            on_message(f"{case.key}: {result.finding.text}")
        results.append(result)
    return results, alpha


def _run_case(case: ImageCase, ours: Engine, reference_engine: Engine, analytic: AnalyticEngine | None,
              params: dict[str, str], s: int, alpha: float, run_seed: int,
              on_message: Callable[[str], None] | None) -> ImageResult:
    """One case: the reference engine's reference, the tested engine's batches, the closed form if there is
    one (`analytic`), and the comparisons; a failed render gives a failed result carrying the reason."""
    source = "none"
    references: dict[str, Reference] = {}

    def failed(reason: str, mine: RenderResult | None = None) -> ImageResult:
        return ImageResult(case, mine, references, {}, source, s, None, alpha, run_seed, reason, tested=ours.name)

    try:
        reference, source = load_reference(case, reference_engine)
        if reference is None:
            if on_message:
                on_message(f"{case.key}: {source}; rendering it now (`make references` stores it)")
            reference = render_reference(case, reference_engine)
            source = f"rendered now ({source})"
    except Exception as e:
        return failed(f"{reference_engine.name.capitalize()} reference: {_reason(e)}")
    references[reference_engine.name] = reference
    try:
        mine = ours.render(str(case.path), case.integrator, OUR_SPP[case.integrator], IMAGE_BATCHES, s, params)
    except RenderFailed as e:
        return failed(f"our render: {e.reason}")
    if analytic is not None:
        try:
            exact = analytic.render(str(case.path), case.integrator,
                                    analytic.samples_for(case.integrator, OUR_SPP[case.integrator]), IMAGE_BATCHES,
                                    s + 1, params)
        except Exception as e:
            return failed(f"closed form: {_reason(e)}", mine)
        references[analytic.name] = Reference(summarize(exact.batches), exact.spp, exact.seconds, CLOSED_FORM)
    summary = summarize(mine.batches)
    signed = entry(case.integrator).signed
    comparisons = {name: compare_summaries(summary, ref.summary, alpha, signed=signed, samples=(mine.spp, ref.spp))
                   for name, ref in references.items()}
    finding = decide(comparisons, summary, {name: ref.summary for name, ref in references.items()}, alpha, signed,
                     {name: ref.spp for name, ref in references.items()}, reference_engine.name,
                     analytic.name if analytic is not None else "")
    return ImageResult(case, mine, references, comparisons, source, s, None, alpha, run_seed, finding=finding,
                       tested=ours.name)
