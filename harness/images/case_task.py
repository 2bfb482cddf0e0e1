"""One image case as a task that runs anywhere: in this process, or on a Dask worker with the scene's
files sent by content. What comes back is the case's result without our batches when it passed (the
report needs only their means), and the messages the case printed."""
from __future__ import annotations

import traceback
from collections.abc import Sequence
from concurrent.futures import Future
from dataclasses import dataclass, replace
from typing import Callable

from harness.comparison.compare import compare_summaries
from harness.comparison.summary import summarize
from harness.comparison.cause import named_cause
from harness.comparison.mismatch import diagnose
from harness.distributed.bundle import Bundle, bundle_files
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine, RenderFailed, RenderResult
from harness.engines.dialects import image_convention
from harness.images.copy_lines import in_user_terms
from harness.foreign_text import one_line
from harness.images.oracle import decide
from harness.images.reference_image import ReferenceImage, against_image, fit_verdict
from harness.images.render_ahead import RenderAhead, closed_form_args, render_args
from harness.images.references import (CLOSED_FORM, Reference, load_reference, reference_path, render_params,
                                       render_reference)
from harness.images.result import ImageResult
from harness.images.scene_constants import scene_constants
from harness.images.spp_search import decisive_budget
from harness.images.suite import ROOT, USER, ImageCase
from harness.integrators import entry


@dataclass
class CaseJob:
    case: ImageCase
    seed: int                # the case's own seed (run.case_seed)
    alpha: float             # per-comparison level of the whole run
    run_seed: int
    closed_form: bool        # whether the analytic engine renders this case too
    test: Engine             # the engine under test
    reference: Engine
    #: A reference image (--reference-image) in place of the reference engine's render.
    reference_image: ReferenceImage | None = None
    #: Our renders and the closed forms started ahead (a serial run, harness/images/render_ahead.py), and this
    #: case's place in them.
    ahead: RenderAhead | None = None
    closed_forms_ahead: RenderAhead | None = None
    index: int = 0


def draws_our_estimator(case: ImageCase, reference: Engine) -> bool:
    """Whether the reference engine draws the case's estimator, sample for sample, as it says
    (Engine.draws_same_estimator)."""
    return reference.draws_same_estimator(case.path, case.integrator)


def share_scene_bundles(executor, cases, engines: Sequence[Engine]) -> dict[str, object]:
    """Per scene of `cases`, a handle to its bundle on the executor's cluster, each sent once; nothing
    for an executor that runs here (its tasks read the files in place). `engines`: those that will render
    the cases (each may read its own scene file, and its stored references)."""
    bundles: dict[str, object] = {}
    if executor.ships_files:
        for case in cases:
            if case.scene not in bundles:
                bundles[case.scene] = executor.share(scene_bundle(case, engines))
    return bundles


def on_files(case: ImageCase, bundle: Bundle | None) -> ImageCase:
    """`case` reading the bundle's copy of its files (written on first use), or its own without one."""
    return case if bundle is None else replace(case, root=bundle.materialize())


def scene_bundle(case: ImageCase, engines: Sequence[Engine] = ()) -> Bundle:
    """The files every case of `case.scene` reads: its scene file and each engine's (Engine.scene_file),
    their meshes, and each engine's stored references of the scene."""
    extra = {}
    for engine in engines:
        stored = reference_path(case, engine).parent
        if stored.is_dir():
            extra.update({str(p.relative_to(ROOT)): p for p in sorted(stored.glob("*"))})
    files = list(dict.fromkeys([case.path, *(e.scene_file(case.path) for e in engines)]))
    # A user's scene travels from its prepared copy's folder; its meshes are named by absolute paths.
    return bundle_files(case.root if case.group == USER else ROOT, files, extra)


def run_case_job(job: CaseJob, bundle: Bundle | None = None):
    """(ImageResult, messages). With a bundle, the case reads the bundle's copy of its files. An exception no
    stage foresaw fails the case with one line (its traceback in the result, for the run's log)."""
    try:
        return _run_case_job(job, bundle)
    except Exception as e:
        reason = one_line(f"internal error: {type(e).__name__}: {in_user_terms(str(e), job.case)}")
        return ImageResult(job.case, None, {}, {}, "none", job.seed, None, job.alpha, job.run_seed, reason,
                           tested=job.test.name, traceback=traceback.format_exc()), []


def _run_case_job(job: CaseJob, bundle: Bundle | None = None):
    case = on_files(job.case, bundle)
    messages: list[str] = []
    if job.reference_image is not None:
        result = run_image_case(case, job.test, job.reference_image, job.seed, job.alpha, job.run_seed)
    else:
        started = not case.problem  # a case that cannot be rendered asks for no render
        result = run_case(case, job.test, job.reference, AnalyticEngine() if job.closed_form else None,
                          render_params(case), job.seed, job.alpha, job.run_seed, messages.append,
                          job.ahead.render(job.index) if job.ahead and started else None,
                          job.closed_forms_ahead.render(job.index) if job.closed_forms_ahead and started
                          and job.closed_form else None)
    result.case = job.case
    if result.ours is not None and (not result.failed or result.error is not None):
        result.ours = result.ours.light()  # a failed comparison keeps its batches for results/<run>/images/
    return result, messages


def reference_task(case: ImageCase, engine: Engine, bundle: Bundle | None = None):
    """The reference engine's render of `case` at the reference budget, summarised (references command)."""
    from harness.images.references import render_reference

    return render_reference(on_files(case, bundle), engine)


def _reason(e: Exception) -> str:
    """One line saying why a render failed."""
    if isinstance(e, RenderFailed):
        return e.reason
    text = str(e).strip().splitlines()
    if text and type(e) is RuntimeError:  # how Mitsuba raises its own errors ("[parser.cpp:N] ..."): its words
        return text[0]
    return f"{type(e).__name__}: {text[0]}" if text else type(e).__name__


class _StageFailed(Exception):
    """A render of the case that failed: the line its result gives, and what the engine printed last."""

    def __init__(self, reason: str, output: str = "") -> None:
        super().__init__(reason)
        self.reason, self.output = reason, output


def _output(e: Exception) -> str:
    return e.output if isinstance(e, RenderFailed) else ""


def run_case(case: ImageCase, ours: Engine, reference_engine: Engine, analytic: AnalyticEngine | None,
              params: dict[str, str], s: int, alpha: float, run_seed: int,
              on_message: Callable[[str], None] | None, mine_ahead: Future | None = None,
              exact_ahead: Future | None = None) -> ImageResult:
    """One case: the reference engine's reference, the tested engine's batches (`mine_ahead`: that render,
    started earlier with render_args), the closed form if there is one (`analytic`; `exact_ahead`: its render,
    started earlier with closed_form_args), and the comparisons; a failed render gives a failed result
    carrying the reason."""
    source = "none"
    references: dict[str, Reference] = {}

    def failed(reason: str, mine: RenderResult | None = None, output: str = "") -> ImageResult:
        # A --scene file: the engines read its prepared copy, whose lines the user does not know.
        reason = one_line(in_user_terms(reason, case))
        return ImageResult(case, mine, references, {}, source, s, None, alpha, run_seed, reason, tested=ours.name,
                           error_output=output)

    if case.problem:  # a --scene file no engine can be given (what its preparation refused)
        return failed(case.problem)

    def tested() -> RenderResult:
        try:
            return mine_ahead.result() if mine_ahead is not None else ours.render(*render_args(case, s, params))
        except Exception as e:
            raise _StageFailed(f"{ours.name} render: {_reason(e)}", _output(e)) from e

    mine = None
    try:
        try:
            reference, source = load_reference(case, reference_engine)
        except Exception as e:
            raise _StageFailed(f"{reference_engine.name.capitalize()} reference: {_reason(e)}", _output(e)) from e
        if reference is None:
            # The engine under test renders first: a file it cannot load costs no reference render.
            mine = tested()
            if on_message:
                on_message(f"{case.key}: {source}; rendering it now" +
                           ("" if case.group == USER else " (`make references` stores it)"))
            try:
                reference = render_reference(case, reference_engine)
            except Exception as e:
                raise _StageFailed(f"{reference_engine.name.capitalize()} reference: {_reason(e)}",
                                   _output(e)) from e
            source = f"rendered now ({source})"
        references[reference_engine.name] = reference
        mine = mine or tested()
    except _StageFailed as e:
        return failed(e.reason, mine, e.output)
    if analytic is not None:
        try:
            exact = exact_ahead.result() if exact_ahead is not None else analytic.render(
                *closed_form_args(case, s, params))
        except Exception as e:
            return failed(f"closed form: {_reason(e)}", mine)
        references[analytic.name] = Reference(summarize(exact.batches), exact.spp, exact.seconds, CLOSED_FORM)
    summary = summarize(mine.batches)
    analytic_name = analytic.name if analytic is not None else None
    signed = entry(case.integrator).signed
    # The closed form draws our estimator (harness/engines/analytic.py: our camera rays, each shaded exactly or
    # by the entry's `sample`); the reference engine does where it says so.
    same = {name: name == analytic_name or draws_our_estimator(case, reference_engine) for name in references}
    comparisons = {name: compare_summaries(summary, ref.summary, alpha, signed=signed, samples=(mine.spp, ref.spp),
                                           same_estimator=same[name])
                   for name, ref in references.items()}
    finding = decide(comparisons, summary, {name: ref.summary for name, ref in references.items()}, alpha, signed,
                     {name: ref.spp for name, ref in references.items()}, reference_engine.name,
                     analytic.name if analytic is not None else "")
    result = ImageResult(case, mine, references, comparisons, source, s, None, alpha, run_seed, finding=finding,
                         tested=ours.name)
    if result.failed:
        failed = next(name for name, c in comparisons.items() if not c.passed)
        result.note = named_cause(summary, references[failed].summary, signed, scene_constants(case.path))
    if result.verdict == "INCONCLUSIVE":
        ref = references[reference_engine.name]
        result.decisive_budget = decisive_budget(summary, mine.spp, ref.summary, ref.spp, alpha, signed,
                                                 same[reference_engine.name])
    return result


def run_image_case(case: ImageCase, ours: Engine, ref: ReferenceImage, s: int, alpha: float,
                   run_seed: int) -> ImageResult:
    """One case against a reference image: the tested engine's batches at the image's size, the fit of the
    image's noise to its model, and the comparison under that model (harness/images/reference_image.py)."""
    source = ref.describe()

    def failed(reason: str, mine: RenderResult | None = None, output: str = "") -> ImageResult:
        return ImageResult(case, mine, {}, {}, source, s, None, alpha, run_seed, one_line(in_user_terms(reason, case)),
                           tested=ours.name, error_output=output)

    if case.problem:
        return failed(case.problem)
    try:
        image = ref.read()
    except ValueError as e:
        return failed(str(e))
    try:
        # The image's width; the height keeps the film's aspect.
        mine = ours.render(*render_args(case, s, {"res": str(image.shape[1])}))
    except RenderFailed as e:
        return failed(f"{ours.name} render: {e.reason}", output=e.output)
    convention = image_convention(case.dialect, case.integrator)
    if convention is not None:  # the image is Nori's: ours as Nori's integrator of that name writes it
        mine = replace(mine, batches=convention.apply(mine.batches))
    try:
        inputs = against_image(ref, image, summarize(mine.batches), mine.batches, mine.spp)
    except ValueError as e:
        return failed(str(e), mine)
    signed = entry(case.integrator).signed
    # The image as K batches of N / K samples, so that its variance floors ours where our batches missed.
    comparison = compare_summaries(inputs.test, inputs.reference, alpha, signed=signed,
                                   samples=(mine.spp, max(1, ref.spp // inputs.reference.image.k)))
    reference = Reference(inputs.reference, ref.spp, {}, source)
    # What a failed comparison looks like (|n| for n, a named factor; else a zoom, a shift, a factor, a
    # background): the user's next step.
    note = None if comparison.passed else (
        named_cause(inputs.test, inputs.reference, signed, scene_constants(case.path)) or diagnose(mine.mean, image))
    if convention is not None:
        note = "; ".join(n for n in (f"compared as {convention.what} (the scene is in Nori's dialect)", note) if n)
    return ImageResult(case, mine, {"image": reference}, {"image": comparison}, source, s, note, alpha, run_seed,
                       tested=ours.name, reference_fit=inputs.fit, reference_problem=fit_verdict(ref, inputs.fit))
