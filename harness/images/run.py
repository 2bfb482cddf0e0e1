"""Running the image suite: the tested engine's renders against the reference engine's (and closed forms),
every case one task, with one family-wise level over the run."""
from __future__ import annotations

import zlib
from typing import Callable

from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine
from harness.images.case_task import CaseJob, run_case_job, share_scene_bundles
from harness.images.references import RESOLUTION, render_params
from harness.images.render_ahead import RenderAhead, closed_form_args, render_args
from harness.images.reference_image import ReferenceImage
from harness.images.result import GEOMETRY_NOTE, ImageResult
from harness.images.suite import ImageCase
from harness.integrators import entry
from harness.statistics.constants import SIGNIFICANCE, sidak_level


def case_seed(case: ImageCase, seed: int) -> int:
    """Distinct seeds per case, so two integrators on one scene do not share their noise."""
    return (zlib.crc32(case.key.encode()) + 7919 * seed) % 2**31


def closed_forms(cases: list[ImageCase]) -> dict[ImageCase, bool]:
    """Per case, whether the analytic engine has its closed form (then a second reference)."""
    params = {"res": str(RESOLUTION)}
    return {c: not c.problem and _supports(c, params) for c in cases}


def _supports(case: ImageCase, params: dict[str, str]) -> bool:
    try:
        return AnalyticEngine.supports(str(case.path), params, case.integrator)
    except Exception:  # a scene file the closed forms' reader cannot take is no closed-form scene
        return False


def comparison_level(cases: list[ImageCase], has_closed_form: dict[ImageCase, bool]) -> float:
    """The per-comparison level of a run of `cases`: its Sidak share of the family-wise SIGNIFICANCE."""
    return sidak_level(SIGNIFICANCE, len(cases) + sum(has_closed_form.values()))


def run_images(cases: list[ImageCase], ours: Engine, reference: Engine, seed: int = 0,
               on_status: Callable[[Status], None] | None = None,
               on_message: Callable[[str], None] | None = None,
               executor: Executor | None = None,
               reference_image: ReferenceImage | None = None) -> tuple[list[ImageResult], float]:
    """Every case, one task each on `executor` (default: here, one after another); all comparisons of the
    run share a family-wise false-alarm rate of SIGNIFICANCE (Sidak). Returns the results, in the order of
    `cases`, and the per-comparison alpha. A render that fails (our RenderFailed, or any exception of a
    reference engine), or a task whose worker dies, fails its case with the reason, and the run goes on."""
    executor = executor or SerialExecutor()
    has_closed_form = closed_forms(cases) if reference_image is None else dict.fromkeys(cases, False)
    alpha = comparison_level(cases, has_closed_form)
    bundles = share_scene_bundles(executor, cases, (ours, reference))
    # Run here, one case after another, our render of the next case and the closed forms overlap the
    # comparisons of this one (harness/images/render_ahead.py).
    ahead = closed = None
    if isinstance(executor, SerialExecutor) and ours.renders_elsewhere and reference_image is None:
        ahead = RenderAhead(ours, [render_args(c, case_seed(c, seed), render_params(c)) for c in cases])
        closed = RenderAhead(AnalyticEngine(), [closed_form_args(c, case_seed(c, seed), render_params(c))
                                                if has_closed_form[c] else None for c in cases], depth=None)
    tasks = [Task(case.key, run_case_job,
                  (CaseJob(case, case_seed(case, seed), alpha, seed, has_closed_form[case], ours, reference,
                           reference_image, ahead, closed, k),
                   bundles.get(case.scene)))
             for k, case in enumerate(cases)]
    try:
        outcomes = executor.run(tasks, on_status)
    finally:
        for started in (ahead, closed):
            if started is not None:
                started.close()
    geometry_failed: set[str] = set()
    refused: set[str] = set()
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
        # A case's own cause (a named factor, |n|) comes first; the scene's geometry note after it.
        if case.scene in geometry_failed:
            result.note = "; ".join(n for n in (result.note, GEOMETRY_NOTE) if n)
        if entry(case.integrator).checks_geometry and result.error is None and result.failed:
            geometry_failed.add(case.scene)
            result.note = result.note or GEOMETRY_NOTE
        if result.error is not None and on_message and case.scene not in refused:
            # What the preparation of a scene refused is said once for the scene, not once per case.
            on_message(f"{case.scene if case.problem else case.key}: {result.error}")
            if case.problem:
                refused.add(case.scene)
        if result.finding is not None and on_message:
            on_message(f"{case.key}: {result.finding.text}")
        results.append(result)
    return results, alpha
