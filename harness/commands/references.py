"""`references`: render and store the Mitsuba references, the only command that writes references/."""
from __future__ import annotations

import argparse

from harness.commands.options import add_engines, add_variant
from harness.commands.output import console, task_progress
from harness.commands.run_folder import RunFolder
from harness.distributed.cluster import add_executor_options
from harness.verdict import Verdict

NAME = "references"
HELP = "render and store Mitsuba references under references/"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Render Mitsuba 3 references (K batches) for the scene suite and store them with their "
                     "provenance, then Mitsuba's invariance cells of the same cases (see `invariance --help`), "
                     "which validate reads instead of rendering them. The only command that writes references/.")
    p.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE", help="as for `images`")
    p.add_argument("--invariances-only", action="store_true",
                   help="store only the reference engine's invariance cells, not its images")
    add_engines(p, test=False)
    add_variant(p)
    add_executor_options(p)


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.distributed.cluster import open_executor
    from harness.distributed.executor import Task
    from harness.engines.registry import make_engine
    from harness.images.case_task import reference_task, share_scene_bundles
    from harness.images.references import write_reference
    from harness.images.suite import select_cases

    cases = select_cases(args.scenes)
    if not cases:
        console.print("[red]FAIL[/] nothing was stored: no case of the suite was selected")
        return Verdict.NOTHING_JUDGED
    mitsuba = make_engine(args.reference, variant=args.variant)
    failed = 0
    with open_executor(args) as executor:
        if not args.invariances_only:
            with task_progress("references", executor) as show:
                bundles = share_scene_bundles(executor, cases, (mitsuba,))
                tasks = [Task(c.key, reference_task, (c, mitsuba, bundles.get(c.scene))) for c in cases]
                outcomes = executor.run(tasks, show)
            for case, outcome in zip(cases, outcomes):
                if outcome.ok:
                    console.print(f"wrote {write_reference(case, mitsuba, outcome.value)}")
                else:
                    failed += 1
                    console.print(f"[red]failed[/] {case.key}: {outcome.error}")
        failed += store_invariance_cells(mitsuba, {c.key for c in cases}, executor)
    return Verdict.FAIL if failed else Verdict.PASS


def store_invariance_cells(engine, keys: set[str], executor) -> int:
    """Render and store the engine's invariance cells of the suite's cases among `keys`, at the level of the
    whole suite (what validate's family uses); returns how many cases failed to render."""
    from harness.images.references import REFERENCE_SEED
    from harness.invariance.check import TASK_FAILED, applicable, family_alpha, run_invariances
    from harness.invariance.stored import write_cells
    from harness.invariance.suite import select
    from harness.statistics.constants import IMAGE_BATCHES

    every, invariances = select(None)
    cases = [c for c in every if c.key in keys]
    with task_progress("invariance cells", executor) as show:
        cells, alpha = run_invariances([engine], cases, invariances, REFERENCE_SEED, on_status=show,
                                       executor=executor, alpha=family_alpha(every, invariances))
    failed = 0
    for case in cases:
        mine = [c for c in cells if c.case.key == case.key]
        broken = [c for c in mine if c.base_error and c.base_error.startswith(TASK_FAILED)]
        if broken:
            failed += 1
            console.print(f"[red]failed[/] invariance cells of {case.key}: {broken[0].base_error}")
            continue
        console.print(f"wrote {write_cells(engine, case, applicable(invariances, case), mine, alpha, IMAGE_BATCHES)}")
    return failed
