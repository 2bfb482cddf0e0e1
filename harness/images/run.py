"""Running the image suite: the tested engine's renders against the reference engine's (and closed forms),
every case one task, with one family-wise level over the run."""
from __future__ import annotations

import zlib
from typing import Callable

from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine
from harness.images.case_renders import CaseRenders
from harness.images.case_task import CaseJob, run_case_job, share_scene_bundles
from harness.images.evaluate import failure, with_scene_notes
from harness.images.references import RESOLUTION
from harness.images.render_ahead import RendersAhead
from harness.images.reference_image import ReferenceImage
from harness.images.result import ImageResult
from harness.images.strategy_renders import not_judged
from harness.images.suite import ImageCase
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


def strategy_checks(cases: list[ImageCase], tested: Engine) -> dict[ImageCase, str | None]:
    """Per case, None where the tested engine's strategies of its integrator are compared, else why not
    ("no strategies" for an integrator without)."""
    return {c: not_judged(c, tested) for c in cases}


def comparison_level(cases: list[ImageCase], has_closed_form: dict[ImageCase, bool],
                     strategies: dict[ImageCase, str | None] | None = None) -> float:
    """The per-comparison level of a run of `cases`: its Sidak share of the family-wise SIGNIFICANCE, each
    case's comparison with the reference engine, with a closed form and its strategy check counted."""
    checks = sum(why is None for why in (strategies or {}).values())
    return sidak_level(SIGNIFICANCE, len(cases) + sum(has_closed_form.values()) + checks)


def _skipped(why: str | None) -> str:
    """What the report says of a case whose strategies are not compared ("" where there are none to compare)."""
    return "" if why in (None, "no strategies") else why


def run_images(cases: list[ImageCase], tested: Engine, reference: Engine, seed: int = 0,
               on_status: Callable[[Status], None] | None = None,
               on_message: Callable[[str], None] | None = None,
               executor: Executor | None = None,
               reference_image: ReferenceImage | None = None) -> tuple[list[ImageResult], float]:
    """Every case, one task each on `executor` (default: here, one after another); all comparisons of the
    run share a family-wise false-alarm rate of SIGNIFICANCE (Sidak). Returns the results, in the order of
    `cases`, and the per-comparison alpha. A render that fails (the tested engine's RenderFailed, or any
    exception of a reference engine), or a task whose worker dies, fails its case with the reason, and the
    run goes on."""
    executor = executor or SerialExecutor()
    has_closed_form = closed_forms(cases) if reference_image is None else dict.fromkeys(cases, False)
    strategies = strategy_checks(cases, tested) if reference_image is None else dict.fromkeys(cases, "no strategies")
    alpha = comparison_level(cases, has_closed_form, strategies)
    bundles = share_scene_bundles(executor, cases, (tested, reference))
    seeds = [case_seed(c, seed) for c in cases]
    # Run here, one case after another, the tested render of the next case and the closed forms overlap the
    # comparisons of this one (harness/images/render_ahead.py); the cases ask for their renders alike.
    if isinstance(executor, SerialExecutor) and tested.renders_elsewhere and reference_image is None:
        renders = RendersAhead(tested, reference, cases, seeds, [has_closed_form[c] for c in cases])
    else:
        renders = CaseRenders(tested, reference)
    tasks = [Task(case.key, run_case_job,
                  (CaseJob(case=case, seed=s, alpha=alpha, run_seed=seed, closed_form=has_closed_form[case],
                           renders=renders, reference_image=reference_image, strategies=strategies[case] is None,
                           strategies_skipped=_skipped(strategies[case])),
                   bundles.get(case.scene)))
             for case, s in zip(cases, seeds)]
    try:
        outcomes = executor.run(tasks, on_status)
    finally:
        renders.close()
    results, said = [], []
    for case, s, outcome in zip(cases, seeds, outcomes):
        if outcome.ok:
            result, messages = outcome.value
        else:
            result, messages = ImageResult(case=case, decision=failure(f"task failed: {outcome.error}"),
                                           tested_engine=tested.name, seed=s, alpha=alpha, run_seed=seed), []
        results.append(result)
        said.append(messages)
    # A case's own cause (a named factor, |n|) comes first; the scene's geometry note after it.
    for result, decision in zip(results, with_scene_notes(cases, [r.decision for r in results])):
        result.decision = decision
    refused: set[str] = set()
    for case, result, messages in zip(cases, results, said):
        for m in messages if on_message else ():
            on_message(m)
        if result.error is not None and on_message and case.scene not in refused:
            # What the preparation of a scene refused is said once for the scene, not once per case.
            on_message(f"{case.scene if case.problem else case.key}: {result.error}")
            if case.problem:
                refused.add(case.scene)
        if result.finding is not None and on_message:
            on_message(f"{case.key}: {result.finding.text}")
    return results, alpha
