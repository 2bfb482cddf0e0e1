"""The commands that stand alone: references, integrators, bench and calibrate (harness.cli runs them)."""
from __future__ import annotations

import time
from pathlib import Path

from harness.cli_output import console, progress_bar
from harness.results import write_atomic, write_json

def _references(args) -> int:
    from harness.engines.mitsuba import MitsubaEngine
    from harness.images.suite import select_cases
    from harness.images.references import render_reference, write_reference

    cases = select_cases(args.scenes)
    mitsuba = MitsubaEngine(args.variant)
    with progress_bar("references") as progress:
        task = progress.add_task("", total=len(cases))
        for case in cases:
            progress.update(task, description=case.key)
            path = write_reference(case, mitsuba, render_reference(case, mitsuba))
            progress.console.print(f"wrote {path}")
            progress.update(task, advance=1)
    return 0


def _integrators() -> int:
    from harness.integrators import match
    from harness.integrators.listing import integrators_table

    console.print(integrators_table(match()))
    return 0


def _bench(args, run_dir: Path) -> tuple[bool, dict]:
    from harness.bench.run import ray_rates, run_bench, seed_comparison
    from harness.engines.mitsuba import MitsubaEngine
    from harness.engines.ours import OurEngine
    from harness.images.suite import select_cases
    from harness.report.bench_html import bench_html

    # By default the simple and ao cases of our own scenes (the real scenes are validated, not benchmarked).
    cases = [c for c in select_cases(args.scenes)
             if args.scenes or (c.integrator != "normals" and c.group == "synthetic")]
    reference = MitsubaEngine()
    factories = {"mcval": OurEngine, "mitsuba": lambda: reference, "mitsuba-scalar": lambda: MitsubaEngine("scalar_rgb")}
    engines = [factories[name]() for name in args.engines]
    ladder = tuple(2**k for k in range(args.max_spp.bit_length()) if 2**k <= args.max_spp)
    start = time.perf_counter()
    with progress_bar("bench") as progress:
        task = progress.add_task("", total=len(cases) * len(engines) * len(ladder))
        benches = run_bench(cases, engines, reference, args.seed, ladder, args.runs,
                            on_step=lambda m: progress.update(task, advance=1, description=m))
        seed = seed_comparison(engines[0], args.seed_runs, lambda m: progress.console.print(m)) \
            if args.seed_runs > 0 and "mcval" in args.engines else None
    rays = ray_rates(args.rays_json)
    meta = {"engines": ", ".join(e.version() for e in engines), "ladder": ladder, "runs per step": args.runs,
            "seconds": round(time.perf_counter() - start, 1)}
    write_atomic(run_dir / "bench.html", bench_html(benches, rays, seed, meta))
    from rich.table import Table
    table = Table(title="Speed against error", header_style="bold")
    for col in ("scene", "integrator", "efficiency ours/mitsuba", *[f"slope {e.name}" for e in engines]):
        table.add_column(col)
    for bch in benches:
        ratio = bch.efficiency_ratio()
        shown = "below ref. noise" if ratio != ratio else f"[{'green' if ratio >= 2 else 'red'}]{ratio:.2f}[/]"
        table.add_row(bch.case.scene, bch.case.integrator, shown,
                      *[f"{c.fit('spp')[0]:.2f}" for c in bch.curves.values()])
    console.print(table)
    payload = {"speed": [bch.to_json() for bch in benches], "seed_comparison": seed, "ray_rates": rays}
    if rays:
        payload["ray_rate_ratio"] = min(v["ratio"] for v in rays["integrators"].values())
    if seed:
        for name, v in seed.items():
            console.print(f"seed settings, {name}: ours {v['seconds']:.2f} s (seed document {v['seed_seconds']} s)")
    console.print(f"Page: {run_dir / 'bench.html'}")
    return True, payload


def _calibrate(args, run_dir: Path) -> bool:
    from harness.engines.ours import OurEngine
    from harness.report.calibration_html import warp_calibration_html
    from harness.report.calibration_table import calibration_table
    from harness.warps.calibration import calibrate_warps
    from harness.warps.suite import select

    specs = select(args.only)
    ours = OurEngine()
    reference = None
    if not args.no_mitsuba:
        from harness.engines.mitsuba import MitsubaEngine
        reference = MitsubaEngine()
    with progress_bar("calibrate") as progress:
        task = progress.add_task("", total=len(specs) * args.seeds)
        cal = calibrate_warps(ours, reference, specs, args.seeds, args.samples,
                              on_seed=lambda: progress.update(task, advance=1))
    meta = {"engine": ours.version(), "reference": reference.version() if reference else "none",
            "seeds per warp": args.seeds, "samples": args.samples, "seconds": round(cal.seconds, 1)}
    write_atomic(run_dir / "calibration.html", warp_calibration_html(cal, meta))
    payload = {"run": run_dir.name, "pass": cal.within, "warps": cal.to_json(), "meta": meta}
    write_json(run_dir / "calibration.json", payload)
    if args.json:
        write_json(args.json, payload)
    console.print(calibration_table(cal))
    console.print(f"{len(specs)} warps x {args.seeds} seeds in {cal.seconds:.0f} s. Page: {run_dir / 'calibration.html'}")
    return cal.within
