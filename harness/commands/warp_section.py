"""The warp conformance matrix as a section of a run (`warps`, `validate`): run, print, write its page."""
from __future__ import annotations

import platform
import time
from pathlib import Path

from rich.markup import escape

from harness.commands.output import console, progress_bar
from harness.statistics.constants import WARP_SAMPLES


def warp_engine(args):
    """The engine whose warps are checked: the --warp-library, else the engine under test. Made once per run
    and kept on `args` (loading a library, reading an engine file)."""
    if "_warp_engine" not in vars(args):
        library = getattr(args, "warp_library", None)
        if library is not None:
            from harness.engines.warp_library import WarpLibraryEngine
            args._warp_engine = WarpLibraryEngine(library)
        else:
            from harness.engines.registry import make_engine
            args._warp_engine = make_engine(args.engine)
    return args._warp_engine


def available_specs(engine, specs) -> tuple[list, list[str]]:
    """The specs `engine` can be checked on, and one line for each it cannot (a sampler without its pdf).
    A warp an optional engine (a user's library) lacks is left out; one the tested engine lacks stays, and fails."""
    from harness.engines.python_child import ChildFailed
    from harness.engines.warp_library import WarpUnavailable

    kept, problems = [], []
    for spec in specs:
        try:
            functions = engine.warp(spec.name, spec.alpha)
        except ChildFailed:  # a library that could not be loaded: each warp asked for fails in its own row
            kept.append(spec)
            continue
        except WarpUnavailable as e:
            if str(e) not in problems:
                problems.append(str(e))
            continue
        if functions is not None or not engine.warps_optional:
            kept.append(spec)
    return kept, problems


def run_warp_section(args, specs, run_dir: Path) -> tuple[bool, dict]:
    """Every warp of `specs` against its pdf and, unless --no-mitsuba, against Mitsuba's; returns (all pass,
    the results.json block)."""
    from harness.engines.registry import make_engine
    from harness.report.reproduce import invocation
    from harness.report.warp_outputs import warp_payload, write_warp_outputs
    from harness.report.warp_table import warp_table
    from harness.warps.suite import run_matrix

    tested = warp_engine(args)
    asked_for = specs
    specs, problems = available_specs(tested, specs)
    for line in problems:
        console.print(f"[red]FAIL[/] {escape(line)}", soft_wrap=True)
    reference = None if getattr(args, "no_mitsuba", False) else make_engine(args.reference)
    samples = getattr(args, "samples", WARP_SAMPLES)
    start = time.perf_counter()
    with progress_bar("warps") as progress:
        task = progress.add_task("", total=len(specs))
        results, level = run_matrix(tested, reference, specs, seed=args.seed, samples=samples,
                                    on_progress=lambda s: progress.update(task, advance=1, description=s.key))
    seconds = time.perf_counter() - start
    meta = {"engine": tested.version(), "reference": reference.version() if reference else "none",
            "samples per warp": samples, "seed": args.seed, "seconds": round(seconds, 2),
            "machine": f"{platform.machine()}, {platform.system()} {platform.release()}"}
    nothing = None
    if results:
        console.print(warp_table(results, level))
    else:
        asked = ", ".join(dict.fromkeys(spec.name for spec in asked_for))
        nothing = f"{tested.name} exports none of the warps asked for ({asked})"
        console.print(f"[red]No warp judged[/]: {escape(nothing)}")
    paths = write_warp_outputs(run_dir, specs, results, level, meta, args.seed, invocation(args))
    failed = [r for r in results if not r.passed]
    console.print(f"{len(results) - len(failed)} of {len(results)} warps pass, in {seconds:.1f} s. "
                  f"Page: {paths['html']}")
    for r in results:
        if r.failure:
            console.print(f"[red]FAIL[/] {escape(r.failure)}", soft_wrap=True)
        elif not r.passed:
            console.print(f"[red]FAIL[/] {r.label}: data in {run_dir / 'warps'}")
    payload = warp_payload(results, level, meta)
    payload["problems"] = problems
    if nothing:
        payload["nothing_judged"] = nothing
    payload["pass"] = ok = payload["pass"] and not problems and bool(results)
    return ok, payload
