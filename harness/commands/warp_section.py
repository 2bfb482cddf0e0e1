"""The warp conformance matrix as a section of a run (`warps`, `validate`): run, print, write its page."""
from __future__ import annotations

import platform
import time
from pathlib import Path

from harness.commands.output import console, progress_bar
from harness.statistics.constants import WARP_SAMPLES


def run_warp_section(args, specs, run_dir: Path) -> tuple[bool, dict]:
    """Every warp of `specs` against its pdf and, unless --no-mitsuba, against Mitsuba's; returns (all pass,
    the results.json block)."""
    from harness.engines.registry import make_engine
    from harness.report.warp_outputs import warp_payload, write_warp_outputs
    from harness.report.warp_table import warp_table
    from harness.warps.suite import run_matrix

    ours = make_engine(args.engine)
    reference = None if getattr(args, "no_mitsuba", False) else make_engine(args.reference)
    samples = getattr(args, "samples", WARP_SAMPLES)
    start = time.perf_counter()
    with progress_bar("warps") as progress:
        task = progress.add_task("", total=len(specs))
        results, level = run_matrix(ours, reference, specs, seed=args.seed, samples=samples,
                                    on_progress=lambda s: progress.update(task, advance=1, description=s.key))
    seconds = time.perf_counter() - start
    meta = {"engine": ours.version(), "reference": reference.version() if reference else "none",
            "samples per warp": samples, "seed": args.seed, "seconds": round(seconds, 2),
            "machine": f"{platform.machine()}, {platform.system()} {platform.release()}"}
    console.print(warp_table(results, level))
    paths = write_warp_outputs(run_dir, specs, results, level, meta, args.seed)
    failed = [r.label for r in results if not r.passed]
    console.print(f"{len(results) - len(failed)} of {len(results)} warps pass, in {seconds:.1f} s. "
                  f"Page: {paths['html']}")
    for label in failed:
        console.print(f"[red]FAIL[/] {label}: data in {run_dir / 'warps'}")
    return not failed, warp_payload(results, level, meta)
