"""One image case as a task that runs anywhere: in this process, or on a Dask worker with the scene's
files sent by content. The task gathers the case's renders (harness/images/gather.py, through the run's
CaseRenders), has them judged (harness/images/evaluate.py) and returns the case's result, without the tested
batches when it passed (the report needs only their means), and the messages the case printed."""
from __future__ import annotations

import traceback
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Callable

from harness.comparison.summary import summarize
from harness.distributed.bundle import Bundle, bundle_files
from harness.engines.base import Engine, RenderFailed
from harness.engines.dialects import image_convention
from harness.images.case_renders import CaseRenders, render_args
from harness.images.copy_lines import in_user_terms
from harness.foreign_text import one_line
from harness.images.evaluate import against_image, evaluate, failure, render_failure
from harness.images.gather import gather
from harness.images.reference_image import ReferenceImage, against_image as image_inputs, fit_verdict
from harness.images.references import Reference, reference_path
from harness.images.result import ImageResult
from harness.images.scene_constants import scene_constants
from harness.images.suite import ROOT, USER, ImageCase


@dataclass(kw_only=True)
class CaseJob:
    case: ImageCase
    seed: int                # the case's own seed (run.case_seed)
    alpha: float             # per-comparison level of the whole run
    run_seed: int
    closed_form: bool        # whether the analytic engine renders this case too
    #: Where the case's renders come from (the tested and the reference engine's, the closed form's).
    renders: CaseRenders
    #: A reference image (--reference-image) in place of the reference engine's render.
    reference_image: ReferenceImage | None = None
    #: Whether the tested engine's strategies of the integrator are rendered and compared; where not, why
    #: (harness/images/strategy_renders.py: not_judged), for the report.
    strategies: bool = False
    strategies_skipped: str = ""

def draws_tested_estimator(case: ImageCase, tested: Engine, reference: Engine) -> bool:
    """Whether the reference engine draws the tested engine's estimator of the case, sample for sample: the tested
    engine draws the integrator's own (Engine.draws_integrator_estimator) and the reference does so on the case's
    scene (Engine.draws_same_estimator). Only then is the tested engine's noise judged against the reference's."""
    return (tested.draws_integrator_estimator(case.integrator)
            and reference.draws_same_estimator(case.path, case.integrator))


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
        return ImageResult(case=job.case, decision=failure(reason), tested_engine=job.renders.tested_engine.name,
                           seed=job.seed, alpha=job.alpha, run_seed=job.run_seed,
                           traceback=traceback.format_exc()), []


def _run_case_job(job: CaseJob, bundle: Bundle | None = None):
    case = on_files(job.case, bundle)
    messages: list[str] = []
    if job.reference_image is not None:
        result = run_image_case(case, job.renders.tested_engine, job.reference_image, job.seed, job.alpha,
                                job.run_seed)
    else:
        result = run_case(case, job.renders, seed=job.seed, alpha=job.alpha, run_seed=job.run_seed,
                          closed_form=job.closed_form, strategies=job.strategies,
                          strategies_skipped=job.strategies_skipped, on_message=messages.append)
    result.case = job.case
    if result.tested is not None and (not result.failed or result.error is not None):
        result.tested = result.tested.light()  # a failed comparison keeps its batches for results/<run>/images/
    return result, messages


def reference_task(case: ImageCase, engine: Engine, bundle: Bundle | None = None):
    """The reference engine's render of `case` at the reference budget, summarised (references command)."""
    from harness.images.references import render_reference

    return render_reference(on_files(case, bundle), engine)


def run_case(case: ImageCase, renders: CaseRenders, *, seed: int, alpha: float, run_seed: int, closed_form: bool,
             strategies: bool = False, strategies_skipped: str = "",
             on_message: Callable[[str], None] | None = None) -> ImageResult:
    """One case: its renders from `renders` (the reference engine's, the tested engine's at `seed`, the closed
    form's where `closed_form`, the tested engine's strategies where `strategies`), judged by evaluate() at
    `alpha`."""
    got = gather(case, renders, seed=seed, closed_form=closed_form, strategies=strategies, on_message=on_message)
    reference = renders.reference_engine.name
    judged = not case.problem and isinstance(got.references.get(reference), Reference)
    decision = evaluate(case, got.tested, got.references, alpha=alpha, reference=reference,
                        reference_draws_estimator=judged and draws_tested_estimator(
                            case, renders.tested_engine, renders.reference_engine),
                        constants=scene_constants(case.path) if judged else {}, strategies=got.strategies,
                        strategies_skipped=strategies_skipped)
    return ImageResult(case=case, decision=decision, tested=got.tested_render,
                       tested_engine=renders.tested_engine.name, references=got.rendered_references,
                       reference_source=got.source, seed=seed, alpha=alpha, run_seed=run_seed)


def run_image_case(case: ImageCase, tested: Engine, ref: ReferenceImage, s: int, alpha: float,
                   run_seed: int) -> ImageResult:
    """One case against a reference image: the tested engine's batches at the image's size, the fit of the
    image's noise to its model, and the comparison under that model (harness/images/reference_image.py),
    judged by harness/images/evaluate.py."""
    source = ref.describe()

    def result(decision, render=None, **more) -> ImageResult:
        return ImageResult(case=case, decision=decision, tested=render, tested_engine=tested.name,
                           reference_source=source, seed=s, alpha=alpha, run_seed=run_seed, **more)

    if case.problem:
        return result(render_failure(case, case.problem))
    try:
        image = ref.read()
    except ValueError as e:
        return result(render_failure(case, str(e)))
    try:
        # The image's width; the height keeps the film's aspect.
        render = tested.render(*render_args(case, s, {"res": str(image.shape[1])}))
    except RenderFailed as e:
        return result(render_failure(case, f"{tested.name} render: {e.reason}", e.output))
    convention = image_convention(case.dialect, case.integrator)
    if convention is not None:  # the image is Nori's: the tested render as Nori's integrator of that name writes it
        render = replace(render, batches=convention.apply(render.batches))
    try:
        inputs = image_inputs(ref, image, summarize(render.batches), render.batches, render.spp)
    except ValueError as e:
        return result(render_failure(case, str(e)), render)
    # The image as K batches of N / K samples, so that its variance floors the tested engine's where its batches
    # missed.
    decision = against_image(case, render, inputs.test, inputs.reference, alpha=alpha,
                             image_samples=max(1, ref.spp // inputs.reference.image.k), image=image,
                             reference_problem=fit_verdict(ref, inputs.fit),
                             convention=convention.what if convention is not None else None,
                             constants=scene_constants(case.path))
    return result(decision, render, references={"image": Reference(inputs.reference, ref.spp, {}, source)},
                  reference_fit=inputs.fit)
