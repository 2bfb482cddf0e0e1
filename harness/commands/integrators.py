"""`integrators`: the renderer's integrators and what the harness knows of each."""
from __future__ import annotations

import argparse

from harness.commands.options import add_engines
from harness.commands.output import console
from harness.commands.run_folder import RunFolder
from harness.verdict import Verdict

NAME = "integrators"
HELP = "the renderer's integrators and what the harness knows of each"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = (
        "List every integrator the tested engine renders (Engine.integrators: for this repository's renderer, "
        "its registry) with its harness entry (harness/integrators/<name>.py, or a .py file in a folder of "
        "$MCVAL_INTEGRATOR_PATH): samples per pixel of the tested engine's renders and of the stored references, "
        "how the reference engine renders it (Engine.integrator_mapping: Mitsuba's plugin and what is removed from "
        "a scene for it), its closed form on one plane, and what it needs of a scene. An integrator without an "
        "entry is listed as such (it is not validated); an entry for an integrator the tested engine lacks is an "
        "error (exit status 2).")
    add_engines(p)


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.engines.registry import engine_integrators, make_engine
    from harness.integrators import match
    from harness.report.integrator_table import integrators_table

    matched = match(engine_integrators(args.engine))
    console.print(integrators_table(matched, make_engine(args.reference)))
    return Verdict.PASS  # a listing, not a judgement
