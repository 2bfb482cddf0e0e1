"""The run that `warps`, `images` and `validate` share: the warp matrix, the invariances, the image cases (each
as asked), in one run folder with one results.json and report.html."""
from __future__ import annotations

from harness.commands.image_section import run_image_section
from harness.commands.invariance_section import run_invariance_section
from harness.commands.output import console
from harness.commands.phases import Phases, seconds_since_process_start
from harness.commands.run_folder import RunFolder


def run_sections(args, run: RunFolder, executor, specs, cases, invariance_only=None, invariances: bool = False,
                 json_copy=None) -> int:
    """Run the warps of `specs`, the invariances (if `invariances`, narrowed by `invariance_only`) and the
    image `cases`; `latest` moves to the run once it is whole, `images-latest` too if it has images."""
    from harness.commands.options import case_selection
    from harness.commands.warp_section import run_warp_section, warp_engine
    from harness.images.suite import not_applicable_cases

    phases = Phases()
    not_applicable = not_applicable_cases(args.scenes, **case_selection(args)) if cases else []
    # The regression baseline is the newest complete run with images (a warps-only run has none).
    baseline = getattr(args, "baseline", None) or ((run.out / "images-latest").resolve() / "results.json")
    run_dir = run.start()
    payload: dict = {"run": run_dir.name}
    ok = True
    warps = None
    if specs and not warp_engine(args).has_warps:
        payload["warps_not_checked"] = f"{warp_engine(args).name} has no warps (give --warp-library LIB.so)"
        console.print(f"[yellow]Warps[/]: {payload['warps_not_checked']}: not checked")
        specs = []
    if specs:
        with phases.timed("warps"):
            warps_ok, warps = run_warp_section(args, specs, run_dir)
        ok &= warps_ok
        payload.update(warps=warps["warps"], warp_level=warps["level"])
        if warps["problems"]:
            payload["warp_problems"] = warps["problems"]
    if invariances:
        # Before the images, so report.html (written with them) carries the matrix.
        console.rule("[bold]Invariances[/] (each engine against itself)")
        with phases.timed("invariances"):
            invariance_ok, payload["invariance"] = run_invariance_section(args, invariance_only, run_dir, executor)
        ok &= invariance_ok
    if cases:
        with phases.timed("images"):
            images_ok, images = run_image_section(args, cases, run_dir, warps, baseline, not_applicable,
                                                  payload.get("invariance"), executor, phases=phases.seconds)
        ok &= images_ok
        payload.update(images)
    payload["pass"] = ok
    index = ("warps.html", "Warp conformance") if not cases and warps is not None else None
    # The phases up to the results; writing them is timed on the terminal's line only.
    payload["phase_seconds"] = dict(phases.seconds)
    payload["wall_seconds"] = round(seconds_since_process_start(), 2)
    with phases.timed("results"):
        run.finish(payload, links=("latest", "images-latest") if cases else ("latest",), index=index,
                   json_copy=json_copy)
    console.print(f"Phases: {phases.line()}")
    console.print(f"Results: {run_dir / 'results.json'} — {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1
