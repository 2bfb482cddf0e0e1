"""The commands that stand alone: references, integrators, bench and calibrate (harness.cli runs them)."""
from __future__ import annotations

import time
from pathlib import Path

from harness.cli_output import console, progress_bar
from harness.results import write_atomic, write_json

def _references(args) -> int:
    from harness.cli_output import task_progress
    from harness.distributed.cluster import open_executor
    from harness.distributed.executor import Task
    from harness.engines.mitsuba import MitsubaEngine
    from harness.images.case_task import reference_task, share_scene_bundles
    from harness.images.suite import select_cases
    from harness.images.references import write_reference

    cases = select_cases(args.scenes)
    mitsuba = MitsubaEngine(args.variant)
    with open_executor(args) as executor, task_progress("references", executor) as show:
        bundles = share_scene_bundles(executor, cases)
        tasks = [Task(c.key, reference_task, (c, mitsuba, bundles.get(c.scene))) for c in cases]
        outcomes = executor.run(tasks, show)
    failed = 0
    for case, outcome in zip(cases, outcomes):
        if outcome.ok:
            console.print(f"wrote {write_reference(case, mitsuba, outcome.value)}")
        else:
            failed += 1
            console.print(f"[red]failed[/] {case.key}: {outcome.error}")
    return 1 if failed else 0


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
    from harness.bench.run import SAME_SAMPLER, SAMPLERS
    reference = MitsubaEngine()
    factories = {"mcval": lambda s: OurEngine(sampler=s, in_process=True), "mitsuba": lambda s: MitsubaEngine(sampler=s),
                 "mitsuba-scalar": lambda s: MitsubaEngine("scalar_rgb", sampler=s)}
    # Each engine with the same sampler (the engine comparison) and, unless --same-sampler, its stratified
    # ones (each engine at its best).
    engines = [factories[name](s) for name in args.engines for s in SAMPLERS[name]
               if s == SAME_SAMPLER or not args.same_sampler]
    ladder = tuple(2**k for k in range(args.max_spp.bit_length()) if 2**k <= args.max_spp)
    start = time.perf_counter()
    if args.workers is not None:
        raise ValueError("bench --workers: workers on one machine would time their renders against each other; "
                         "bench runs serially, or with --scheduler on a cluster of one single-threaded worker "
                         "per machine")
    from harness.distributed.cluster import open_executor
    with open_executor(args) as executor, progress_bar("bench") as progress:
        steps = sum(e.renders_exactly(spp) for e in engines for spp in ladder)
        task = progress.add_task("", total=len(cases) * (1 if executor.ships_files else steps))
        benches = run_bench(cases, engines, reference, args.seed, ladder, args.runs,
                            on_step=lambda m: progress.update(task, advance=1, description=m), executor=executor,
                            on_status=lambda st: progress.update(task, completed=st.done, description=st.last)
                            if executor.ships_files else None)
        ours = next((e for e in engines if e.name == "mcval"), None)
        seed = seed_comparison(ours, args.seed_runs, lambda m: progress.console.print(m),
                               reference if "mitsuba" in args.engines else None) \
            if args.seed_runs > 0 and ours is not None else None
        throughput = None
        if args.throughput_runs > 0 and {"mcval", "mitsuba"} <= set(args.engines):
            from harness.bench.throughput import CASES, measure
            throughput = []
            for case in CASES:
                progress.console.print(f"throughput: {case[0]}:{case[1]} {case[2]}² {case[3]} spp")
                throughput.append(measure(*case, runs=args.throughput_runs).to_json())
        slopes = None
        if "mcval" in args.engines:
            from harness.bench.sampler_slopes import sampler_slopes
            progress.console.print("sampler slopes: cornell simple and ao, 32², our samplers")
            slopes = sampler_slopes()
    rays = ray_rates(args.rays_json)
    meta = {"engines": ", ".join(e.version() for e in engines), "ladder": ladder, "runs per step": args.runs,
            "seconds": round(time.perf_counter() - start, 1)}
    write_atomic(run_dir / "bench.html", bench_html(benches, rays, seed, meta, throughput, slopes))
    from rich.table import Table
    table = Table(title="Speed against error", header_style="bold")
    for col in ("scene", "integrator", "efficiency ours/mitsuba, same sampler", "best against best",
                *[f"slope {e.label}" for e in engines]):
        table.add_column(col)
    for bch in benches:
        ratio = bch.efficiency_ratio()
        shown = "below ref. noise" if ratio != ratio else f"[{'green' if ratio >= 1 else 'red'}]{ratio:.2f}[/]"
        best = bch.comparison(None)
        best_text = "below ref. noise" if best["ratio"] != best["ratio"] else \
            f"{best['ratio']:.2f} ({best['ours']} / {best['reference']})"
        table.add_row(bch.case.scene, bch.case.integrator, shown, best_text,
                      *[f"{c.fit('spp')[0]:.2f}" for c in bch.curves.values()])
    console.print(table)
    payload = {"speed": [bch.to_json() for bch in benches], "seed_comparison": seed, "ray_rates": rays,
               "throughput": throughput, "sampler_slopes": slopes}
    for t in throughput or []:
        console.print(f"throughput {t['scene']}:{t['integrator']} {t['resolution']}² {t['spp']} spp "
                      f"({t['sampler']}): ours {t['median_seconds']['mcval']:.3f} s, Mitsuba "
                      f"{t['median_seconds']['mitsuba']:.3f} s, Mitsuba/ours {t['mitsuba_over_ours']:.2f}")
    for integrator, by_sampler in (slopes or {}).get("slopes", {}).items():
        console.print(f"MSE slope on cornell {integrator}: " + ", ".join(f"{k} {v:.2f}" for k, v in by_sampler.items()))
    if rays:
        payload["ray_rate_ratio"] = min(v["ratio"] for v in rays["integrators"].values())
    if seed:
        for name, v in seed.items():
            mitsuba = f", Mitsuba {v['reference_seconds']:.2f} s" if "reference_seconds" in v else ""
            console.print(f"seed settings, {name}: ours {v['seconds']:.2f} s{mitsuba} (seed document "
                          f"{v['seed_seconds']} s)")
    console.print(f"Page: {run_dir / 'bench.html'}")
    return True, payload


def _calibrate(args, run_dir: Path) -> bool:
    """The warp checks' and the image comparisons' false-alarm rates (both unless --warps or --images), on
    one executor."""
    from harness.distributed.cluster import open_executor

    with open_executor(args) as executor:
        return _calibrate_on(args, run_dir, executor)


def _calibrate_on(args, run_dir: Path, executor) -> bool:
    from harness.engines.ours import OurEngine
    from harness.report.calibration_html import calibration_page, warp_calibration_html

    warps, images = (args.warps or not args.images), (args.images or not args.warps)
    ours = OurEngine()
    reference = None
    if not args.no_mitsuba:
        from harness.engines.mitsuba import MitsubaEngine
        reference = MitsubaEngine()
    payload: dict = {"run": run_dir.name}
    meta: dict = {"engine": ours.version(), "reference": reference.version() if reference else "none"}
    ok, sections = True, []
    if images:
        if reference is None:
            raise ValueError("--images needs Mitsuba (its null comparisons include Mitsuba against itself): "
                             "drop --no-mitsuba")
        cal_images = _calibrate_images(args, ours, reference, executor)
        from harness.report.image_calibration_html import image_calibration_sections
        payload["images"] = cal_images
        sections = image_calibration_sections(cal_images)
        meta.update({"image comparisons": cal_images["comparisons"], "image seconds": round(cal_images["seconds"], 1),
                     "image comparisons ran on": cal_images["ran_on"]})
        ok &= cal_images["pass"]
    if warps:
        cal = _calibrate_warps(args, ours, reference, executor)
        payload["warps"] = cal.to_json()
        meta.update({"seeds per warp": args.seeds, "samples": args.samples, "warp seconds": round(cal.seconds, 1),
                     "warps ran on": executor.description})
        ok &= cal.sound
        page = warp_calibration_html(cal, meta, sections)
    else:
        page = calibration_page("Calibration of the image comparisons", "Each rejection of a null comparison "
                                "is a false alarm.", sections, meta)
    payload.update({"pass": ok, "meta": meta})
    write_atomic(run_dir / "calibration.html", page)
    write_json(run_dir / "calibration.json", payload)
    if args.json:
        write_json(args.json, payload)
    console.print(f"Page: {run_dir / 'calibration.html'}")
    return ok


def _calibrate_warps(args, ours, reference, executor):
    from harness.cli_output import task_progress
    from harness.report.calibration_table import calibration_table
    from harness.warps.calibration import calibrate_warps
    from harness.warps.suite import select

    specs = select(args.only)
    with task_progress("calibrate warps", executor) as show:
        cal = calibrate_warps(ours, reference, specs, args.seeds, args.samples, executor, show)
    console.print(calibration_table(cal))
    for line in cal.failed:
        console.print(f"[red]failed[/] {line}")
    console.print(f"{len(specs)} warps x {args.seeds} seeds in {cal.seconds:.0f} s on {executor.description}.")
    return cal


def _calibrate_images(args, ours, reference, executor) -> dict:
    from harness.cli_output import task_progress
    from harness.images.calibration import calibrate_images
    from harness.report.calibration_table import image_calibration_table

    with task_progress("calibrate images", executor) as show:
        cal = calibrate_images(ours, reference, args.comparisons, args.seed, executor, show)
    where = executor.description
    out = {**cal.to_json(), "ran_on": where}
    console.print(image_calibration_table(out))
    for line in cal.failed:
        console.print(f"[red]failed[/] {line}")
    console.print(f"{out['comparisons']} null image comparisons in {cal.seconds:.0f} s on {where}.")
    return out
