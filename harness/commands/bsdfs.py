"""`bsdfs`: the BSDF matrix: every BSDF of a library (ours by default) at every incident angle, against its own
pdf, energy and reciprocity, and against Mitsuba's plugin of the same name."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.bsdfs.suite import ALPHA, ANGLES, OUR_DEFAULTS, SAMPLES
from harness.commands.options import add_common
from harness.commands.run_folder import RunFolder
from harness.verdict import Tally, Verdict, run_verdict

NAME = "bsdfs"
HELP = "the BSDF matrix: sampling, weights, energy, reciprocity, against Mitsuba"
OUR_LIBRARY = Path(__file__).resolve().parents[2] / "build" / "libmcval_bsdfs.so"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Check BSDFs at several incident angles: their sampling against their pdf (chi-square), the "
                     "weight of every sample (value / pdf), the pdf's normalisation, the energy (albedo <= 1) and "
                     "reciprocity, and, where the name is one of Mitsuba's plugins, value, pdf and samples against "
                     "Mitsuba's (docs/bsdfs.md).")
    add_common(p)
    p.add_argument("--bsdf-library", type=Path, metavar="LIB.so",
                   help="check the BSDFs this shared library exports (the C ABI of include/mcval_bsdfs.h) instead "
                        "of our renderer's (build/libmcval_bsdfs.so)")
    p.add_argument("--bsdf", nargs="+", metavar="NAME[:p=v,...]",
                   help="the BSDFs to check and their parameter values, e.g. diffuse:reflectance=0.5 "
                        "roughconductor:alpha=0.1,ggx=1 (default: ours at a low and a high roughness, or every "
                        "BSDF the library exports at default values)")
    p.add_argument("--angles", nargs="+", type=float, default=list(ANGLES), metavar="DEGREES",
                   help=f"incident angles from the normal (default: {' '.join(f'{a:g}' for a in ANGLES)})")
    p.add_argument("--samples", type=int, default=SAMPLES, help=f"samples per BSDF and angle (default: {SAMPLES})")
    p.add_argument("--alpha", type=float, default=ALPHA,
                   help=f"family-wise level of the run's statistical checks (default: {ALPHA})")
    p.add_argument("--no-mitsuba", action="store_true", help="skip the checks against Mitsuba's plugins")
    p.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")


def _entries(args, library, mitsuba) -> list:
    """The BSDFs asked for, each ready or with the one line saying why it cannot be checked."""
    from harness.bsdfs.hard_inputs import roughness_extremes
    from harness.bsdfs.suite import Entry, parse_spec
    from harness.engines.bsdf_library import BsdfUnavailable

    texts = args.bsdf or (OUR_DEFAULTS if args.bsdf_library is None else library.names)
    entries = []
    for spec in map(parse_spec, texts):
        try:
            values = spec.values(library.parameters(spec.name))
            bsdf = library.functions(spec.name, values)
        except (BsdfUnavailable, ValueError) as e:
            entries.append(Entry(spec.name, failure=str(e)))
            continue
        reference = None if mitsuba is None else mitsuba.functions(spec.name, values)
        extremes = roughness_extremes(lambda v, name=spec.name: library.functions(name, v), values)
        entries.append(Entry(bsdf.label, bsdf, reference, extremes=extremes))
    return entries


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from rich.markup import escape

    from harness.bsdfs.suite import run_matrix
    from harness.commands.output import console, print_verdict, progress_bar
    from harness.engines.bsdf_library import BsdfLibrary
    from harness.engines.mitsuba_bsdfs import MitsubaBsdfs
    from harness.report.bsdf_outputs import bsdf_junit, bsdf_table

    if args.samples < 1000:
        raise ValueError(f"--samples {args.samples}: at least 1000 (the chi-square needs counts to test)")
    library = BsdfLibrary(args.bsdf_library or OUR_LIBRARY)
    mitsuba = None if args.no_mitsuba else MitsubaBsdfs()
    entries = _entries(args, library, mitsuba)
    run_dir = run.start()
    with progress_bar("bsdfs") as progress:
        task = progress.add_task("", total=sum(1 if e.failure else len(args.angles) for e in entries))
        rows, level = run_matrix(entries, args.angles, args.samples, args.seed, args.alpha,
                                 on_progress=lambda s: progress.update(task, advance=1, description=s))
    console.print(bsdf_table(rows, level))
    for row in rows:
        if not row.passed:
            where = "" if row.theta is None else f" at {row.theta:g} degrees"
            lines = [row.failure] if row.failure else [f"{k}: {c.summary}" for k, c in row.checks.items() if not c.passed]
            console.print(f"[red]FAIL[/] {escape(row.label + where + ': ' + '; '.join(lines))}", soft_wrap=True)
    passed = sum(r.passed for r in rows)
    verdict, reason = run_verdict([Tally("BSDF rows", passed, len(rows) - passed)])
    meta = {"library": library.version(), "reference": "Mitsuba 3 plugins" if mitsuba else "none",
            "samples": args.samples, "seed": args.seed, "alpha": args.alpha, "level": level}
    (run_dir / "junit.xml").write_text(bsdf_junit(rows, meta))
    run.finish({"run": run_dir.name, "bsdfs": [r.to_json() for r in rows], "bsdf_level": level, "meta": meta,
                "pass": verdict is Verdict.PASS, "verdict": verdict.value, "verdict_reason": reason},
               json_copy=args.json)
    console.print(f"{passed} of {len(rows)} BSDF rows pass.")
    print_verdict(run_dir / "results.json", verdict, reason)
    return verdict
