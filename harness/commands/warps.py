"""`warps`: the warp conformance matrix alone."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.commands.options import add_common, add_engines, add_warp_library
from harness.commands.run_folder import RunFolder
from harness.statistics.constants import WARP_SAMPLES
from harness.verdict import Verdict

NAME = "warps"
HELP = "the warp conformance matrix alone"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Check every warp of the renderer against its pdf (chi-square, normalisation, domain, hard "
                     "inputs) and against Mitsuba 3's implementation.")
    add_common(p)
    add_engines(p)
    p.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")
    p.add_argument("--only", nargs="+", metavar="WARP",
                   help="check only these warps, e.g. tent beckmann:0.01 (default: all)")
    p.add_argument("--samples", type=int, default=WARP_SAMPLES,
                   help=f"samples per warp for the statistical tests (default: {WARP_SAMPLES})")
    p.add_argument("--no-mitsuba", action="store_true", help="skip the checks against the reference engine")
    add_warp_library(p)


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.commands.sections import run_sections
    from harness.commands.warp_section import warp_engine
    from harness.warps.suite import select

    if not warp_engine(args).has_warps:
        raise ValueError(f"{warp_engine(args).name} has no warps: give them with --warp-library LIB.so "
                         "(docs/engines.md)")
    return run_sections(args, run, None, select(args.only), [], json_copy=args.json, images=False)
