"""`calibrate`: the measured false-alarm rate of every statistical check (warps, image comparisons, BSDFs) and
the power of the image comparison and of the BSDF checks."""
from __future__ import annotations

import argparse
from pathlib import Path

from rich.markup import escape

from harness.commands.options import add_common, add_engines, add_warp_library
from harness.commands.output import console, task_progress
from harness.commands.run_folder import RunFolder
from harness.distributed.cluster import add_executor_options
from harness.results import write_atomic
from harness.bsdfs.calibration import NULL_ROWS
from harness.bsdfs.suite import SAMPLES as BSDF_SAMPLES
from harness.statistics.constants import WARP_SAMPLES
from harness.verdict import Tally, Verdict, run_verdict

NAME = "calibrate"
HELP = "measure the false-alarm rate of every statistical check"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = (
        "Measure, not assume, how often each statistical check rejects when nothing is wrong. Warps: every "
        "correct warp of the matrix at many seeds (chi-square, homogeneity with Mitsuba). Images: null "
        "comparisons (the tested engine against itself at independent seeds, Mitsuba against Mitsuba, the "
        "tested engine against the closed form) per scale and for the whole comparison, and the smallest whole-image and 8x8-tile biases found "
        "90 %% of the time. Each rate with an exact interval beside the nominal level. Writes calibration.html "
        "and calibration.json (blocks with `comparisons` and `false_alarm_rate`); results/calibration-latest "
        "points at the newest. Exits 1 if a rate lies above its nominal level beyond its interval (the check "
        "raises more false alarms than it says) or a comparison failed, 3 if no null run was made; a rate below "
        "its interval (conservative: it costs power, not false FAILs) is shown in yellow. BSDFs (--bsdfs, not in "
        "the default: about 10 minutes on two workers): correct BSDFs of a library (ours by default) against "
        "Mitsuba's plugins at many seeds, every check as the matrix runs it; a deterministic check must never "
        "fail them; and the power of the energy and weight checks on planted defects of the stated size.")
    add_common(p)
    add_engines(p)
    p.add_argument("--warps", action="store_true", help="calibrate the warp checks (with --images: both; the default)")
    p.add_argument("--images", action="store_true", help="calibrate the image comparisons (default: both)")
    p.add_argument("--bsdfs", action="store_true", help="calibrate the BSDF checks (alone, or with --warps, --images)")
    p.add_argument("--only", nargs="+", metavar="WARP", help="only these warps, e.g. tent beckmann:0.01")
    p.add_argument("--bsdf", nargs="+", metavar="NAME[:p=v,...]@DEGREES",
                   help="the BSDF null rows, e.g. roughconductor:alpha=0.1@60 (default: "
                        f"{' '.join(NULL_ROWS)}; a Lambertian on the energy check's edge is always added)")
    p.add_argument("--bsdf-library", type=Path, metavar="LIB.so",
                   help="calibrate on the BSDFs of this library (include/mcval_bsdfs.h) instead of ours")
    p.add_argument("--seeds", type=int, default=200, help="null runs per warp and per BSDF row (default 200)")
    p.add_argument("--samples", type=int,
                   help=f"samples per run, as in the matrix (default {WARP_SAMPLES} for warps, {BSDF_SAMPLES} for "
                        "BSDFs)")
    p.add_argument("--comparisons", type=int, default=80,
                   help="null image comparisons of each of the three kinds (default 80: 240 in all)")
    p.add_argument("--json", type=Path, metavar="PATH", help="also write the figures as JSON to PATH")
    p.add_argument("--no-mitsuba", action="store_true", help="skip the checks against Mitsuba (warps only)")
    add_warp_library(p)
    add_executor_options(p)


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    """Both calibrations unless --warps or --images, on one executor."""
    from harness.distributed.cluster import open_executor

    run_dir = run.start()
    with open_executor(args) as executor:
        tallies, payload, page = _calibrate(args, run_dir, executor)
    verdict, reason = run_verdict(tallies)
    payload.update({"pass": verdict is Verdict.PASS, "verdict": verdict.value, "verdict_reason": reason})
    write_atomic(run_dir / "calibration.html", page)
    run.finish(payload, links=("calibration-latest",), json_copy=args.json, name="calibration.json")
    console.print(f"Page: {run_dir / 'calibration.html'}")
    if reason:
        console.print(f"[red]FAIL[/] {escape(reason)}", soft_wrap=True)
    return verdict


def calibration_tally(what: str, runs: int, sound: bool, why_none: str) -> Tally:
    """One calibration as a verdict: judged when it ran null runs (`runs`), passed when its rates are sound."""
    if runs == 0:
        return Tally(what, failed=0 if sound else 1, not_judged=(why_none,))
    return Tally(what, passed=int(sound), failed=int(not sound))


def _calibrate(args, run_dir: Path, executor) -> tuple[list[Tally], dict, str]:
    from harness.engines.registry import make_engine
    from harness.report.calibration_html import calibration_page, warp_calibration_html
    from harness.report.bsdf_calibration_html import bsdf_calibration_sections
    from harness.report.image_calibration_html import image_calibration_sections

    from harness.commands.warp_section import warp_engine

    chosen = args.warps or args.images or args.bsdfs
    warps, images, bsdfs = args.warps or not chosen, args.images or not chosen, args.bsdfs
    tested = make_engine(args.engine)
    warp_source = warp_engine(args) if warps else None
    if warps and not warp_source.has_warps:
        if args.warps:
            raise ValueError(f"--warps: {warp_source.name} has no warps; give them with --warp-library LIB.so")
        console.print(f"Warps: {warp_source.name} has none (give --warp-library LIB.so): not calibrated")
        warps = False
    reference = None if args.no_mitsuba else make_engine(args.reference)
    payload: dict = {"run": run_dir.name}
    meta: dict = {"engine": tested.version(), "reference": reference.version() if reference else "none"}
    tallies, sections = [], []
    if images:
        if reference is None:
            raise ValueError("--images needs Mitsuba (its null comparisons include Mitsuba against itself): "
                             "drop --no-mitsuba")
        cal_images = _calibrate_images(args, tested, reference, executor)
        payload["images"] = cal_images
        sections = image_calibration_sections(cal_images)
        meta.update({"image comparisons": cal_images["comparisons"], "image seconds": round(cal_images["seconds"], 1),
                     "image comparisons ran on": cal_images["ran_on"]})
        tallies.append(calibration_tally("null image comparisons", cal_images["comparisons"], cal_images["pass"],
                                         f"--comparisons {args.comparisons} gave none"))
    if bsdfs:
        cal_bsdfs = _calibrate_bsdfs(args, reference is not None, executor)
        payload["bsdfs"] = cal_bsdfs.to_json()
        sections += bsdf_calibration_sections(cal_bsdfs)
        meta.update({"seeds per BSDF row": args.seeds, "BSDF samples": cal_bsdfs.samples,
                     "BSDF seconds": round(cal_bsdfs.seconds, 1), "BSDFs ran on": executor.description})
        tallies.append(calibration_tally("null BSDF runs", cal_bsdfs.null_runs, cal_bsdfs.sound,
                                         f"--seeds {args.seeds} gave none"))
    if warps:
        cal = _calibrate_warps(args, warp_source, reference, executor)
        payload["warps"] = cal.to_json()
        meta.update({"seeds per warp": args.seeds, "samples": cal.samples, "warp seconds": round(cal.seconds, 1),
                     "warps ran on": executor.description})
        runs = args.seeds * len(cal.entries)
        tallies.append(calibration_tally("null warp runs", runs, cal.sound,
                                         f"--seeds {args.seeds} over {len(cal.entries)} warp checks gave none"))
        page = warp_calibration_html(cal, meta, sections)
    else:
        what = "image comparisons" if not bsdfs else "BSDF checks" if not images else "statistical checks"
        page = calibration_page(f"Calibration of the {what}", "Each rejection of a null run is a false alarm.",
                                sections, meta)
    payload["meta"] = meta
    return tallies, payload, page


def _calibrate_warps(args, tested, reference, executor):
    from harness.report.calibration_table import calibration_table
    from harness.warps.calibration import calibrate_warps
    from harness.warps.suite import select

    specs = select(args.only)
    samples = args.samples or WARP_SAMPLES
    with task_progress("calibrate warps", executor) as show:
        cal = calibrate_warps(tested, reference, specs, args.seeds, samples, executor, show)
    console.print(calibration_table(cal))
    for line in cal.failed:
        console.print(f"[red]failed[/] {line}")
    console.print(f"{len(specs)} warps x {args.seeds} seeds in {cal.seconds:.0f} s on {executor.description}.")
    return cal


def _calibrate_bsdfs(args, against_mitsuba: bool, executor):
    from functools import partial

    from harness.bsdfs.calibration import calibrate_bsdfs, parse_row
    from harness.commands.bsdf_section import OUR_LIBRARY, null_row_functions
    from harness.report.calibration_table import bsdf_power_table, calibration_table

    rows = list(args.bsdf or NULL_ROWS)
    for row in rows:
        parse_row(row)  # a mistyped row is refused before any runs
    library = args.bsdf_library or OUR_LIBRARY
    if not library.is_file():
        raise ValueError(f"--bsdf-library {library}: no such file")
    with task_progress("calibrate bsdfs", executor) as show:
        functions_of = partial(null_row_functions, str(library), against_mitsuba)
        cal = calibrate_bsdfs(functions_of, rows, args.seeds, args.samples or BSDF_SAMPLES, executor, show)
    console.print(calibration_table(cal, "BSDF"))
    console.print(bsdf_power_table(cal))
    for d in cal.deterministic:
        if d.failures:
            console.print(f"[red]false FAIL[/] {escape(f'{d.row}: {d.check} failed {d.failures} of {d.runs} runs ({d.example})')}",
                          soft_wrap=True)
    for line in cal.failed:
        console.print(f"[red]failed[/] {escape(line)}", soft_wrap=True)
    if cal.degenerate:
        console.print(f"p = 1 at every seed (nothing random tested; not in the rates): {escape('; '.join(cal.degenerate))}",
                      soft_wrap=True)
    console.print(f"{len(rows) + 1} BSDF rows x {args.seeds} seeds in {cal.seconds:.0f} s on {executor.description}.")
    return cal


def _calibrate_images(args, tested, reference, executor) -> dict:
    from harness.images.calibration import calibrate_images
    from harness.report.calibration_table import image_calibration_table

    with task_progress("calibrate images", executor) as show:
        cal = calibrate_images(tested, reference, args.comparisons, args.seed, executor, show)
    where = executor.description
    out = {**cal.to_json(), "ran_on": where}
    console.print(image_calibration_table(out))
    for line in cal.failed:
        console.print(f"[red]failed[/] {line}")
    console.print(f"{out['comparisons']} null image comparisons in {cal.seconds:.0f} s on {where}.")
    return out
