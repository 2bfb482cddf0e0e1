"""The run that `warps`, `images` and `validate` share: the warp matrix, the invariances, the image cases (each
as asked), in one run folder with one results.json and report.html."""
from __future__ import annotations

from harness.commands.image_section import run_image_section
from harness.commands.invariance_section import run_invariance_section
from harness.commands.output import console, print_verdict
from harness.commands.phases import Phases, seconds_since_process_start
from harness.commands.run_folder import RunFolder
from harness.verdict import Tally, Verdict, run_verdict


def run_sections(args, run: RunFolder, executor, specs, cases, invariance_only=None, invariances: bool = False,
                 json_copy=None, images: bool = True, bsdfs: bool = False, bsdf_specs=None) -> Verdict:
    """Run the warps of `specs`, the BSDF matrix (if `bsdfs`: `bsdf_specs`, None for the default set), the
    invariances (if `invariances`, narrowed by `invariance_only`) and, if `images`, the image `cases`; `latest`
    moves to the run once it is whole, `images-latest` too if it has images. The run PASSes only if nothing failed
    and each suite that ran judged something (harness/verdict.py)."""
    from harness.commands.options import case_selection
    from harness.commands.warp_section import WarpSection, warp_engine
    from harness.images.suite import not_applicable_cases

    phases = Phases()
    not_applicable = not_applicable_cases(args.scenes, **case_selection(args)) if images else []
    # The regression baseline is the newest complete run with images (a warps-only run has none).
    baseline = getattr(args, "baseline", None) or ((run.out / "images-latest").resolve() / "results.json")
    run_dir = run.start()
    payload: dict = {"run": run_dir.name}
    tallies: list[Tally] = []
    ok = True
    warps = None
    if specs and not warp_engine(args).has_warps:
        payload["warps_not_checked"] = f"{warp_engine(args).name} has no warps (give --warp-library LIB.so)"
        console.print(f"[yellow]Warps[/]: {payload['warps_not_checked']}: not checked")
        specs = []
    warp_section = None
    if specs:
        with phases.timed("warps"):
            warp_section = WarpSection(args, specs)  # its checks go on beside the BSDF rows
    if bsdfs:
        with phases.timed("bsdfs"):
            ok &= _bsdf_section(args, bsdf_specs, run_dir, payload, tallies)
    if warp_section is not None:
        # "warps" counts what the matrix takes beyond the BSDFs: the wait for it, its throughput, its page.
        with phases.timed("warps"):
            warps_ok, warps = warp_section.finish(run_dir)
        ok &= warps_ok or not warps["warps"]  # a matrix with no warp judged nothing: its tally says so
        tallies.append(warp_tally(warps))
        payload.update(warps=warps["warps"], warp_level=warps["level"])
        if warps["problems"]:
            payload["warp_problems"] = warps["problems"]
    if invariances:
        # Before the images, so report.html (written with them) carries the matrix.
        console.rule("[bold]Invariances[/] (each engine against itself)")
        with phases.timed("invariances"):
            tally, payload["invariance"] = run_invariance_section(args, invariance_only, run_dir, executor)
        tallies.append(tally)
    if images and cases:
        with phases.timed("images"):
            tally, found = run_image_section(args, cases, run_dir, warps, baseline, not_applicable,
                                             payload.get("invariance"), executor, phases=phases.seconds)
        tallies.append(tally)
        payload.update(found)
    elif images:
        tallies.append(_no_image_cases(args, not_applicable))
    verdict, reason = run_verdict(tallies, ok)
    payload.update({"pass": verdict is Verdict.PASS, "verdict": verdict.value, "verdict_reason": reason,
                    "judged": [t.to_json() for t in tallies]})
    index = ("warps.html", "Warp conformance") if not cases and warps is not None else None
    # The phases up to the results; writing them is timed on the terminal's line only.
    payload["phase_seconds"] = dict(phases.seconds)
    payload["wall_seconds"] = round(seconds_since_process_start(), 2)
    with phases.timed("results"):
        run.finish(payload, links=("latest", "images-latest") if cases else ("latest",), index=index,
                   json_copy=json_copy)
    console.print(f"Phases: {phases.line()}")
    print_verdict(run_dir / "results.json", verdict, reason)
    return verdict


def _bsdf_section(args, specs, run_dir, payload: dict, tallies: list[Tally]) -> bool:
    """The BSDF matrix of the engine under test's library (or --bsdf-library) into `payload` and `tallies`; an
    engine without one is said to have no BSDFs checked, as one without warps. Returns whether every row passed."""
    from harness.bsdfs.suite import ALPHA, ANGLES, SAMPLES
    from harness.commands.bsdf_section import bsdf_library_of, run_bsdf_section

    library = bsdf_library_of(args)
    if library is None:
        payload["bsdfs_not_checked"] = f"{args.engine} has no BSDF library (give --bsdf-library LIB.so)"
        console.print(f"[yellow]BSDFs[/]: {payload['bsdfs_not_checked']}: not checked")
        return True
    console.rule("[bold]BSDFs[/]")
    tally, block = run_bsdf_section(library, specs, ANGLES, SAMPLES, args.seed, ALPHA, True, run_dir,
                                    junit_name="bsdfs-junit.xml")
    payload.update(block)
    tallies.append(tally)
    return tally.failed == 0


def warp_tally(warps: dict) -> Tally:
    """The warp matrix's part of the verdict: each warp checked passes or fails; a warp the library lacks is a
    failure (`problems`)."""
    passed = sum(bool(w["pass"]) for w in warps["warps"])
    return Tally("warps", passed, len(warps["warps"]) - passed + len(warps["problems"]),
                 () if warps["warps"] else (warps.get("nothing_judged", "the engine has none of the warps asked for"),))


def _no_image_cases(args, not_applicable) -> Tally:
    """The image suite's tally when no case was selected, with why."""
    from harness.commands.options import case_selection
    from harness.engines.registry import make_engine
    from harness.images.judged import image_tally, why_no_cases

    reason = why_no_cases(make_engine(args.engine).name, case_selection(args)["integrators"], not_applicable)
    return image_tally([], not_applicable, reason)
