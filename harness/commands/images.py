"""`images`: every scene with every integrator against Mitsuba 3 (stored references) and closed forms."""
from __future__ import annotations

import argparse

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


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.commands.options import case_selection
    from harness.commands.sections import run_sections
    from harness.distributed.cluster import open_executor
    from harness.images.suite import select_cases

    cases = chosen_image_case(args, select_cases(args.scenes, **case_selection(args)))
    with open_executor(args) as executor:
        return run_sections(args, run, executor, [], cases)
