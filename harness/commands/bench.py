"""`bench`: speed against error, convergence curves and efficiency ratios (timed one job at a time)."""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from harness.commands.options import add_common, add_engines, add_scene_files
from harness.commands.output import console, print_verdict, progress_bar
from harness.commands.run_folder import RunFolder
from harness.distributed.cluster import add_executor_options
from harness.results import write_atomic
from harness.verdict import Verdict

NAME = "bench"
HELP = "speed against error: convergence curves and efficiency ratios"
#: The engines the tested one is timed against unless --engines says otherwise (harness/engines/registry.py).
TIMED_AGAINST = ("mitsuba-native", "mitsuba-scalar")
#: Mitsuba as shipped traces with Embree's faster, non-robust triangle test. Where the tested engine's render
#: throughput is measured against it, it is measured against Mitsuba with robust intersections too (Embree as
#: mcval runs it): like for like beside as shipped.
ALSO_TIMED = {"mitsuba-native": ("mitsuba-robust",)}


def throughput_against(compared: str) -> tuple[str, ...]:
    """The engines the tested one's render throughput is measured against, where its efficiency is compared
    with `compared`: that engine, and the engines ALSO_TIMED names for it."""
    return (compared, *ALSO_TIMED.get(compared, ()))


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.description = ("Render every case at a ladder of sample counts with the tested engine and those it is timed "
                     "against (by default this repository's renderer and Mitsuba, llvm and scalar), several runs per "
                     "step, one job at a time; write bench.html.")
    add_common(p)
    p.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE",
                   help="as for `images` (default: the cases of scenes/ whose integrator is benchmarked: simple, ao, "
                        "direct and path; the real scenes are validated, not benchmarked)")
    add_scene_files(p)
    add_engines(p)
    p.add_argument("--engines", nargs="+", metavar="NAME",
                   help="engines to run, by registry name or engine file, the engine under test first; its "
                        "efficiency is compared with the next (default: --engine, then mitsuba-native and "
                        "mitsuba-scalar; Mitsuba as shipped is the speed to beat)")
    p.add_argument("--max-spp", type=int, default=256, help="top of the ladder 1, 2, 4, ... (default 256)")
    p.add_argument("--same-sampler", action="store_true",
                   help="only the engine comparison: every engine with the independent sampler (by default each "
                        "also runs its stratified samplers: mcval sobol, Mitsuba ldsampler and multijitter, and the "
                        "tested engine's samplers' convergence slopes are measured)")
    p.add_argument("--runs", type=int, default=3, help="independent runs per step (default 3)")
    p.add_argument("--rays-json", type=Path, help="figures written by build/bench_rays --json, to include")
    p.add_argument("--throughput-runs", type=int, default=3,
                   help="timed runs per case of the side-by-side render throughput (highpoly 768², cornell 128²), "
                        "against the engine the efficiency is compared with and, where that is Mitsuba as shipped, "
                        "against Mitsuba with robust intersections too (0 skips it; default 3)")
    p.add_argument("--seed-runs", type=int, default=3,
                   help="runs at the seed document's settings (768x768; 0 skips them; default 3)")
    add_executor_options(p)


def _engines(args):
    """Each engine with the same sampler (the engine comparison) and, unless --same-sampler, its stratified
    ones (each engine at its best); renders in this process where the engine can, as the others do."""
    from harness.bench.run import SAME_SAMPLER
    from harness.engines.registry import make_engine

    return [make_engine(name, sampler=s, in_process=True) for name in args.engines
            for s in make_engine(name, in_process=True).samplers if s == SAME_SAMPLER or not args.same_sampler]


def _measure(args, cases, engines, reference, ladder):
    """The ladders, the seed settings, the throughput and the sampler slopes, as asked. The tested engine
    (the first of --engines) is timed against the next one (Mitsuba as shipped, by default), else --reference;
    its throughput against those throughput_against names (Mitsuba robust too, by default)."""
    from harness.bench.run import SAME_SAMPLER, run_bench, seed_comparison
    from harness.distributed.cluster import open_executor
    from harness.engines.registry import make_engine

    tested_name = args.engines[0]
    compared_name = next((name for name in args.engines[1:] if name != tested_name), args.reference)
    with open_executor(args) as executor, progress_bar("bench") as progress:
        steps = sum(e.renders_exactly(spp) for e in engines for spp in ladder)
        task = progress.add_task("", total=len(cases) * (1 if executor.ships_files else steps))
        benches = run_bench(cases, engines, reference, args.seed, ladder, args.runs,
                            on_step=lambda m: progress.update(task, advance=1, description=m), executor=executor,
                            on_status=lambda st: progress.update(task, completed=st.done, description=st.last)
                            if executor.ships_files else None)
        seed = None
        if args.seed_runs > 0:  # with the scene's own sampler
            seed = seed_comparison(make_engine(tested_name, in_process=True), args.seed_runs,
                                   lambda m: progress.console.print(m), make_engine(compared_name))
        throughput = None
        if args.throughput_runs > 0:
            from harness.bench.throughput import CASES, measure
            tested = make_engine(tested_name, sampler=SAME_SAMPLER, in_process=True)
            # The tested engine as `images` runs it, where that is in another process (mcval's: its worker).
            worker = make_engine(tested_name, sampler=SAME_SAMPLER)
            worker = worker if worker.renders_elsewhere and not tested.renders_elsewhere else None
            against = [make_engine(name, sampler=SAME_SAMPLER) for name in throughput_against(compared_name)]
            throughput = []
            for case in CASES:
                for compared in against:
                    progress.console.print(f"throughput: {case[0]}:{case[1]} {case[2]}² {case[3]} spp against "
                                           f"{compared.label or compared.name}")
                    throughput.append(measure(*case, tested, compared, worker, runs=args.throughput_runs,
                                              sampler=SAME_SAMPLER).to_json())
        slopes = None
        samplers = make_engine(tested_name).samplers
        if len(samplers) > 1 and not args.same_sampler:  # the slopes compare the tested engine's samplers
            from harness.bench.sampler_slopes import sampler_slopes
            progress.console.print(f"sampler slopes: cornell simple and ao, 32², {', '.join(samplers)}")
            slopes = sampler_slopes({s: make_engine(tested_name, sampler=s, in_process=True) for s in samplers})
    return benches, seed, throughput, slopes


def _why_nothing(args, selected) -> str:
    """Why bench has no case to measure: none selected (why_no_cases), or none of them is benchmarked."""
    from harness.commands.options import case_selection
    from harness.images.judged import why_no_cases
    from harness.images.suite import not_applicable_cases
    from harness.integrators import entries

    selection = case_selection(args)
    if not selected:
        return why_no_cases(args.engines[0], selection["integrators"], not_applicable_cases(args.scenes, **selection))
    measured = ", ".join(e.name for e in entries().values() if e.benchmarked)
    return (f"none of the {len(selected)} cases is benchmarked: bench measures {measured} on the scenes of "
            "scenes/ (name a case with --scenes to measure it)")


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.bench.run import ray_rates
    from harness.engines.registry import DEFAULT_TEST, make_engine
    from harness.images.suite import select_cases
    from harness.integrators import entry
    from harness.report.bench_html import bench_html
    from harness.report.bench_table import bench_lines, bench_table

    if args.engines and args.engine not in (DEFAULT_TEST, args.engines[0]):
        raise ValueError(f"bench --engine {args.engine} --engines {' '.join(args.engines)}: the engine under test is "
                         "the first of --engines; give one or the other")
    args.engines = args.engines or [args.engine, *TIMED_AGAINST]
    args.engine = args.engines[0]
    run_dir = run.start()
    # By default the benchmarked integrators' cases of our own scenes (the real scenes are validated, not benchmarked).
    from harness.commands.options import case_selection

    selected = select_cases(args.scenes, **case_selection(args))
    cases = [c for c in selected if args.scenes or (entry(c.integrator).benchmarked and c.group != "real")]
    if not cases:  # nothing to measure: the run says why, and is no success
        reason = f"nothing was measured: {_why_nothing(args, selected)}"
        run.finish({"run": run_dir.name, "pass": False, "verdict": Verdict.NOTHING_JUDGED.value,
                    "verdict_reason": reason}, links=())
        print_verdict(run_dir / "results.json", Verdict.NOTHING_JUDGED, reason)
        return Verdict.NOTHING_JUDGED
    unreadable = next((c for c in cases if c.problem), None)
    if unreadable is not None:  # a --scene file no engine can be given: there is nothing to time
        raise ValueError(unreadable.problem)
    reference = make_engine(args.reference)
    engines = _engines(args)
    ladder = tuple(2**k for k in range(args.max_spp.bit_length()) if 2**k <= args.max_spp)
    start = time.perf_counter()
    if args.workers is not None:
        raise ValueError("bench --workers: workers on one machine would time their renders against each other; "
                         "bench runs serially, or with --scheduler on a cluster of one single-threaded worker "
                         "per machine")
    benches, seed, throughput, slopes = _measure(args, cases, engines, reference, ladder)
    rays = ray_rates(args.rays_json)
    meta = {"engines": ", ".join(e.version() for e in engines), "ladder": ladder, "runs per step": args.runs,
            "seconds": round(time.perf_counter() - start, 1)}
    write_atomic(run_dir / "bench.html", bench_html(benches, rays, seed, meta, throughput, slopes))
    console.print(bench_table(benches, engines))
    payload = {"speed": [bch.to_json() for bch in benches], "seed_comparison": seed, "ray_rates": rays,
               "throughput": throughput, "sampler_slopes": slopes}
    for line in bench_lines(payload):
        console.print(line)
    if rays:
        payload["ray_rate_ratio"] = min(v["ratio"] for v in rays["integrators"].values())
    console.print(f"Page: {run_dir / 'bench.html'}")
    run.finish({"run": run_dir.name, "pass": True, **payload}, links=("bench-latest", "latest"),
               index=("bench.html", "Speed against error"))
    return Verdict.PASS
