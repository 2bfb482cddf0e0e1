"""`integrators`: the renderer's integrators and what the harness knows of each."""
from __future__ import annotations

import argparse

from harness.commands.output import console
from harness.commands.run_folder import RunFolder
from harness.verdict import Verdict

NAME = "integrators"
HELP = "the renderer's integrators and what the harness knows of each"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = (
        "List every integrator of the renderer's registry (mcval_renderer.integrators()) with its harness entry "
        "(harness/integrators/<name>.py, or a .py file in a folder of $MCVAL_INTEGRATOR_PATH): samples per pixel "
        "of our renders and of Mitsuba's references, the Mitsuba integrator it is compared with and what is "
        "removed from a scene for it, its closed form on one plane, and what it needs of a scene. An integrator "
        "without an entry is listed as such (it is not validated); an entry for an integrator the renderer lacks "
        "is an error (exit status 2).")


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.integrators import match
    from harness.report.integrator_table import integrators_table

    console.print(integrators_table(match()))
    return Verdict.PASS  # a listing, not a judgement
