"""`bsdfs`: the BSDF matrix: every BSDF of a library (ours by default) at every incident angle, against its own
pdf, energy and reciprocity, and against Mitsuba's plugin of the same name."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.bsdfs.suite import ALPHA, ANGLES, SAMPLES
from harness.commands.options import add_common
from harness.commands.run_folder import RunFolder
from harness.verdict import Verdict, run_verdict

NAME = "bsdfs"
HELP = "the BSDF matrix: sampling, weights, energy, reciprocity, against Mitsuba"


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
    p.add_argument("--jobs", type=int, metavar="N",
                   help="rows checked at once, on threads of this process, each with its own processes of the "
                        "library and of Mitsuba (default: one per core); the results do not depend on it")
    p.add_argument("--no-mitsuba", action="store_true", help="skip the checks against Mitsuba's plugins")
    p.add_argument("--mitsuba", action="store_true",
                   help="check Mitsuba's own plugins (conductor, dielectric, diffuse, plastic, roughconductor, "
                        "roughdielectric, roughplastic) instead "
                        "of a library, each on its own")
    p.add_argument("--nori-test", nargs="+", type=Path, metavar="FILE.xml",
                   help="Nori's BSDF test files (<test type=\"chi2test\"> or \"ttest\", e.g. pa5's "
                        "chi2test-microfacet.xml): each <bsdf> is mapped onto the library's BSDF of its type and "
                        "judged as Nori judges it, then by the matrix's checks (instead of --bsdf)")
    p.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.bsdfs.suite import parse_spec
    from harness.commands.bsdf_section import OUR_LIBRARY, run_bsdf_section
    from harness.commands.output import print_verdict
    from harness.engines.bsdf_library import BsdfLibrary
    from harness.engines.mitsuba_bsdfs import MitsubaBsdfs

    if args.jobs is not None and args.jobs < 1:
        raise ValueError(f"--jobs {args.jobs}: expected at least 1")
    if args.samples < 1000:
        raise ValueError(f"--samples {args.samples}: at least 1000 (the chi-square needs counts to test)")
    specs = None if args.bsdf is None else [parse_spec(t) for t in args.bsdf]
    if args.mitsuba and args.bsdf_library:
        raise ValueError("--mitsuba and --bsdf-library: give one (whose BSDFs to check)")
    if args.nori_test and args.bsdf:
        raise ValueError("--nori-test and --bsdf: give one (the test files name their BSDFs)")
    library = MitsubaBsdfs() if args.mitsuba else BsdfLibrary(args.bsdf_library or OUR_LIBRARY)
    tallies, nori = [], {}
    if args.nori_test:
        from harness.commands.nori_test_section import run_nori_tests
        nori_tally, nori, specs = run_nori_tests(args.nori_test, library, args.seed)
        tallies.append(nori_tally)
    run_dir = run.start()
    tally, block = run_bsdf_section(library, specs, args.angles, args.samples, args.seed, args.alpha,
                                    not args.no_mitsuba, run_dir, jobs=args.jobs)
    verdict, reason = run_verdict([*tallies, tally])
    run.finish({"run": run_dir.name, "bsdfs": block["bsdfs"], "bsdf_level": block["bsdf_level"], **nori,
                "meta": block["bsdf_meta"], "pass": verdict is Verdict.PASS, "verdict": verdict.value,
                "verdict_reason": reason}, json_copy=args.json)
    print_verdict(run_dir / "results.json", verdict, reason)
    return verdict
