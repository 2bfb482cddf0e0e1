"""`images`: every scene with every integrator against Mitsuba 3 (stored references) and closed forms."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.commands.options import add_common, add_image_options
from harness.commands.reference_image_options import add_reference_image_options, chosen_image_case
from harness.commands.run_folder import RunFolder
from harness.verdict import Verdict

NAME = "images"
HELP = "every scene with every integrator against Mitsuba 3"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Render the scene suite (or your scenes, --scene) with the engine under test (our renderer, "
                     "or yours through an engine file, --engine) and compare with Mitsuba 3 (stored references when "
                     "their provenance matches) and closed forms.")
    add_common(p)
    add_image_options(p)
    add_reference_image_options(p)
    p.add_argument("--nori-test", nargs="+", type=Path, metavar="FILE.xml",
                   help="instead of the suite, run Nori's scene tests (<test type=\"ttest\"> of <scene>s, as its "
                        "course ships them): each scene rendered by the engine under test and judged by Nori's "
                        "t-test against the file's reference for it")


def _run_nori_tests(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.commands.nori_scene_section import run_nori_scene_tests
    from harness.commands.output import print_verdict
    from harness.engines.registry import make_engine
    from harness.verdict import run_verdict

    engine = make_engine(args.engine)
    run_dir = run.start()
    tally, block = run_nori_scene_tests(args.nori_test, engine, run_dir, args.seed)
    verdict, reason = run_verdict([tally])
    run.finish({"run": run_dir.name, **block, "pass": verdict is Verdict.PASS, "verdict": verdict.value,
                "verdict_reason": reason})
    print_verdict(run_dir / "results.json", verdict, reason)
    return verdict


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    if args.nori_test:
        return _run_nori_tests(args, run)
    from harness.commands.options import case_selection
    from harness.commands.sections import run_sections
    from harness.distributed.cluster import open_executor
    from harness.images.suite import select_cases

    cases = chosen_image_case(args, select_cases(args.scenes, **case_selection(args)))
    with open_executor(args) as executor:
        return run_sections(args, run, executor, [], cases)
