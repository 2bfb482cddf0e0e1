"""`validate`: everything, what `make validate` runs: the warp matrix, the BSDF matrix, the invariances, the image
cases."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.commands.options import add_common, add_reference_live, add_image_options, add_warp_library
from harness.commands.run_folder import RunFolder
from harness.verdict import Verdict

NAME = "validate"
HELP = "everything: what `make validate` runs"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Warp conformance, the BSDF matrix (see `bsdfs --help`), image validation (our scenes, then "
                     "the real scenes of scenes/real/ as their own section) and the invariances (see `invariance --help`); writes "
                     "results/<run>/report.html.")
    add_common(p)
    add_image_options(p)
    p.add_argument("--warps-only", nargs="+", metavar="WARP",
                   help="narrow the Warps section as `warps --only` does, e.g. tent beckmann:0.01 (default: all)")
    p.add_argument("--invariance-only", nargs="+", metavar="NAME",
                   help="narrow the Invariances section as `invariance --only` does (default: its default cases)")
    p.add_argument("--no-invariance", action="store_true", help="skip the Invariances section")
    p.add_argument("--bsdfs-only", nargs="+", metavar="NAME[:p=v,...]",
                   help="narrow the BSDFs section as `bsdfs --bsdf` does, e.g. diffuse roughconductor:alpha=0.1 "
                        "(default: ours, or every BSDF of --bsdf-library)")
    p.add_argument("--no-bsdfs", action="store_true", help="skip the BSDFs section")
    add_reference_live(p)
    add_warp_library(p)
    p.add_argument("--bsdf-library", type=Path, metavar="LIB.so",
                   help="check the BSDFs this shared library exports (include/mcval_bsdfs.h, docs/bsdfs.md); "
                        "without it, an engine other than ours has no BSDFs checked")


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.bsdfs.suite import parse_spec
    from harness.commands.options import case_selection
    from harness.commands.sections import run_sections
    from harness.distributed.cluster import open_executor
    from harness.images.suite import select_cases
    from harness.invariance.suite import select as select_invariance
    from harness.warps.suite import select

    with open_executor(args) as executor:
        specs = select(args.warps_only)  # bad names: no run
        bsdf_specs = None if args.bsdfs_only is None else [parse_spec(t) for t in args.bsdfs_only]
        selection = case_selection(args)
        select_invariance(args.invariance_only, **selection)
        return run_sections(args, run, executor, specs, select_cases(args.scenes, **selection),
                            invariance_only=args.invariance_only, invariances=not args.no_invariance,
                            bsdfs=not args.no_bsdfs, bsdf_specs=bsdf_specs)
