"""`references`: render and store the Mitsuba references, the only command that writes references/."""
from __future__ import annotations

import argparse

from harness.commands.options import add_engines, add_variant
from harness.commands.output import console, task_progress
from harness.commands.run_folder import RunFolder
from harness.distributed.cluster import add_executor_options

NAME = "references"
HELP = "render and store Mitsuba references under references/"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Render Mitsuba 3 references (K batches) for the scene suite and store them with their "
                     "provenance. The only command that writes references/.")
    p.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE", help="as for `images`")
    add_engines(p, test=False)
    add_variant(p)
    add_executor_options(p)


def run(args: argparse.Namespace, run: RunFolder) -> int:
    from harness.distributed.cluster import open_executor
    from harness.distributed.executor import Task
    from harness.engines.registry import make_engine
    from harness.images.case_task import reference_task, share_scene_bundles
    from harness.images.references import write_reference
    from harness.images.suite import select_cases

    cases = select_cases(args.scenes)
    mitsuba = make_engine(args.reference, variant=args.variant)
    with open_executor(args) as executor, task_progress("references", executor) as show:
        bundles = share_scene_bundles(executor, cases, (mitsuba,))
        tasks = [Task(c.key, reference_task, (c, mitsuba, bundles.get(c.scene))) for c in cases]
        outcomes = executor.run(tasks, show)
    failed = 0
    for case, outcome in zip(cases, outcomes):
        if outcome.ok:
            console.print(f"wrote {write_reference(case, mitsuba, outcome.value)}")
        else:
            failed += 1
            console.print(f"[red]failed[/] {case.key}: {outcome.error}")
    return 1 if failed else 0
