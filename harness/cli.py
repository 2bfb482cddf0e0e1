"""The command line: `python -m harness {warps,images,references,validate,integrators,...}`. The only module
that prints."""
from __future__ import annotations

import signal
import sys
import threading
import time
from pathlib import Path

from rich.markup import escape

from harness.cli_args import build_parser
from harness.cli_commands import _bench, _calibrate, _integrators, _references
from harness.cli_output import console, err, progress_bar, task_progress
from harness.results import latest_run, new_run_dir, point_link, write_atomic, write_json
from harness.statistics.constants import WARP_SAMPLES

def _run_warps(args, specs, run_dir: Path) -> tuple[bool, dict]:
    import platform

    from harness.engines.ours import OurEngine
    from harness.report.warp_table import warp_table
    from harness.warps.outputs import warp_payload, write_warp_outputs
    from harness.warps.suite import run_matrix

    ours = OurEngine()
    reference = None
    if not getattr(args, "no_mitsuba", False):
        from harness.engines.mitsuba import MitsubaEngine
        reference = MitsubaEngine()
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


def _print_real_scenes(real, not_applicable, alpha: float) -> None:
    """The real scenes under their own heading: their table, then the cases that do not apply and why."""
    from harness.report.image_table import image_table

    console.rule("[bold]Real scenes[/] (scenes/real/)")
    if real:
        table = image_table(real, alpha)
        table.title = f"Real scenes against Mitsuba 3 (per-comparison α {alpha:.2g}, family-wise 0.01)"
        console.print(table)
    for case, reason in not_applicable:
        console.print(f"{escape(case.key)}: not applicable: {escape(reason)} (not run)")


def _run_images(args, cases, run_dir: Path, warps: dict | None, baseline: Path | None,
                not_applicable=(), invariance: dict | None = None, executor=None) -> tuple[bool, dict]:
    from harness.engines.mitsuba import MitsubaEngine
    from harness.engines.ours import OurEngine
    from harness.images.outputs import write_image_outputs
    from harness.images.real_scenes import real_scenes_json, split
    from harness.integrators import match
    from harness.images.run import run_images
    from harness.report.image_html import reproduce_command
    from harness.report.image_table import image_table

    ours, mitsuba = OurEngine(), MitsubaEngine(args.variant)
    start = time.perf_counter()
    with task_progress("images", executor) as show:
        results, alpha = run_images(cases, ours, mitsuba, args.seed, on_status=show,
                                    on_message=lambda m: err.print(f"[yellow]{escape(m)}[/]", soft_wrap=True),
                                    executor=executor)
        where = executor.description
    seconds = time.perf_counter() - start
    synthetic, real = split(results)
    if synthetic:
        console.print(image_table(synthetic, alpha))
    if real or not_applicable:
        _print_real_scenes(real, not_applicable, alpha)
    for name in match().without_entry:
        console.print(f"[yellow]{escape(name)}[/]: no harness entry (not validated; see `python -m harness "
                      "integrators`)")
    meta = {"engine": ours.version(), "reference": mitsuba.version(), "seed": args.seed,
            "image seconds": round(seconds, 1), "ran on": where}
    payload = write_image_outputs(run_dir, results, alpha, warps, meta, baseline, invariance)
    if real or not_applicable:
        payload["real_scenes"] = real_scenes_json(results, not_applicable)
    regression = payload["regression"] or []
    new = [e for e in regression if e["flags"] == ["new case"]]
    if new:
        console.print(f"{len(new)} case(s) new since {payload['baseline']}")
    for entry in regression:
        if entry["flags"] and entry not in new:
            console.print(f"[yellow]changed[/] {entry['scene']}:{entry['integrator']}: {'; '.join(entry['flags'])}")
    failed = [r for r in results if not r.passed]
    console.print(f"{len(results) - len(failed)} of {len(results)} image comparisons pass, in {seconds:.1f} s. "
                  f"Report: {run_dir / 'report.html'}")
    for r in failed:
        why = "; ".join(x for x in (r.error, r.note) if x)
        console.print(f"[red]FAIL[/] {r.case.key}{' — ' + escape(why) if why else ''}: {reproduce_command(r)}")
    return not failed, payload


def _run_invariance(args, only, run_dir: Path, executor, engines=None) -> tuple[bool, dict]:
    """The invariance matrix: each engine against itself under every transformation. Only our renderer's
    breaks fail; a reference's are printed and stored as findings."""
    from harness.engines.ours import OurEngine
    from harness.invariance.check import run_invariances
    from harness.invariance.findings import failure_lines, invariance_payload
    from harness.invariance.suite import select
    from harness.report.invariance_table import invariance_tables

    cases, invariances = select(only)
    if engines is None:
        engines = [OurEngine()]
        if not getattr(args, "no_mitsuba", False):
            from harness.engines.mitsuba import MitsubaEngine
            engines.append(MitsubaEngine(args.variant))
    gating = engines[0].name
    start = time.perf_counter()
    with task_progress("invariances", executor) as show:
        cells, alpha = run_invariances(engines, cases, invariances, args.seed, on_status=show, executor=executor)
    seconds = time.perf_counter() - start
    for table in invariance_tables(cells, alpha, gating):
        console.print(table)
    meta = {"engines": [e.version() for e in engines], "seed": args.seed, "seconds": round(seconds, 1)}
    payload = invariance_payload(cells, alpha, gating, meta)
    from harness.report.invariance_html import invariance_html
    write_atomic(run_dir / "invariance.html", invariance_html(payload))
    for line in payload["findings"]:
        console.print(f"[yellow]finding[/] {escape(line)}", soft_wrap=True)
    for line in payload["float32_limits"]:
        console.print(f"[cyan]float32[/] {escape(line)}", soft_wrap=True)
    ours = [c for c in cells if c.engine == gating]
    failed = failure_lines(cells, gating)
    beyond = sum(c.status == "float32" for c in ours)
    console.print(f"{len(ours) - len(failed) - beyond} of {len(ours)} invariance checks of {gating} pass"
                  + (f", {beyond} broke only where float32 cannot represent the scene" if beyond else "")
                  + f", in {seconds:.1f} s.")
    for line in failed:
        console.print(f"[red]FAIL[/] invariance {escape(line)}", soft_wrap=True)
    console.print(f"Page: {run_dir / 'invariance.html'}")
    return payload["pass"], payload


def _unfinished(what: str, out: Path, run_dir: Path | None, previous: str | None) -> str:
    """One line: where an unfinished run's partial output is, and that `latest` did not move."""
    if run_dir is None:
        return what
    kept = f"{out / 'latest'} still points at {previous}" if previous else f"{out / 'latest'} was not created"
    return f"{what}: partial output in {run_dir}/; {kept}"


def _run(args, out: Path, started: list[Path]) -> int:
    """The command; its run folder goes into `started` as soon as it exists. The commands that render
    image cases run them on one executor (serial, or Dask: harness/distributed/) for the whole run."""
    if args.command not in ("images", "validate", "invariance"):
        return _run_command(args, out, started, None)
    from harness.distributed.cluster import open_executor
    with open_executor(args) as executor:
        return _run_command(args, out, started, executor)


def _run_command(args, out: Path, started: list[Path], executor) -> int:
    from harness.images.suite import not_applicable_cases, select_cases
    from harness.warps.suite import select
    if args.command == "integrators":
        return _integrators()
    if args.command == "references":
        return _references(args)
    if args.command == "bench":
        started.append(run_dir := new_run_dir(out))
        ok, payload = _bench(args, run_dir)
        write_json(run_dir / "results.json", {"run": run_dir.name, "pass": ok, **payload})
        write_atomic(run_dir / "report.html", '<!DOCTYPE html><meta charset="utf-8">'
                                              '<a href="bench.html">Speed against error</a>')
        point_link(out / "bench-latest", run_dir)
        point_link(out / "latest", run_dir)
        return 0
    if args.command in ("invariance", "validate"):
        from harness.invariance.suite import select as select_invariance
        select_invariance(args.only if args.command == "invariance" else args.invariance_only)  # bad names: no run
    if args.command == "invariance":
        started.append(run_dir := new_run_dir(out))
        ok, invariance = _run_invariance(args, args.only, run_dir, executor)
        payload = {"run": run_dir.name, "pass": ok, "invariance": invariance}
        write_json(run_dir / "results.json", payload)
        write_atomic(run_dir / "report.html", '<!DOCTYPE html><meta charset="utf-8">'
                                              '<a href="invariance.html">Invariances</a>')
        if args.json:
            write_json(args.json, payload)
        point_link(out / "latest", run_dir)
        console.print(f"Results: {run_dir / 'results.json'} — {'PASS' if ok else 'FAIL'}")
        return 0 if ok else 1
    if args.command == "calibrate":
        started.append(run_dir := new_run_dir(out))
        ok = _calibrate(args, run_dir)
        point_link(out / "calibration-latest", run_dir)
        return 0 if ok else 1
    specs = select(getattr(args, "only", None)) if args.command in ("warps", "validate") else []
    cases = select_cases(args.scenes) if args.command in ("images", "validate") else []
    not_applicable = not_applicable_cases(args.scenes) if cases else []
    # `latest` is the newest complete run; it moves to this run only once this run is complete.
    # The regression baseline is the newest complete run with images (a warps-only run has none).
    baseline = getattr(args, "baseline", None) or ((out / "images-latest").resolve() / "results.json")
    started.append(run_dir := new_run_dir(out))
    payload: dict = {"run": run_dir.name}
    ok = True
    warps = None
    if specs:
        warps_ok, warps = _run_warps(args, specs, run_dir)
        ok &= warps_ok
        payload.update(warps=warps["warps"], warp_level=warps["level"])
    if args.command == "validate" and not args.no_invariance:
        # Before the images, so report.html (written with them) carries the matrix.
        console.rule("[bold]Invariances[/] (each engine against itself)")
        invariance_ok, payload["invariance"] = _run_invariance(args, args.invariance_only, run_dir, executor)
        ok &= invariance_ok
    if cases:
        images_ok, images = _run_images(args, cases, run_dir, warps, baseline, not_applicable,
                                        payload.get("invariance"), executor)
        ok &= images_ok
        payload.update(images)
    if not cases and warps is not None:
        write_atomic(run_dir / "report.html",
                     '<!DOCTYPE html><meta charset="utf-8"><a href="warps.html">Warp conformance</a>')
    payload["pass"] = ok
    write_json(run_dir / "results.json", payload)
    if getattr(args, "json", None):
        write_json(args.json, payload)
    point_link(out / "latest", run_dir)
    if cases:
        point_link(out / "images-latest", run_dir)
    console.print(f"Results: {run_dir / 'results.json'} — {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def main(argv: list[str] | None = None) -> int:
    """Exit status: 0 all pass, 1 a check failed, 2 bad input or an error, 130 interrupted (Ctrl-C).
    An unfinished run leaves its partial folder and does not move results/latest."""
    args = build_parser().parse_args(argv)
    out: Path = getattr(args, "out", Path("results"))
    previous = latest_run(out)
    run: list[Path] = []
    # SIGTERM (a CI time-out, `kill`) ends the run as Ctrl-C does: the render child is stopped and
    # the partial output is named.
    in_main_thread = threading.current_thread() is threading.main_thread()
    old_term = signal.signal(signal.SIGTERM, _raise_interrupt) if in_main_thread else None
    try:
        return _run(args, out, run)
    except KeyboardInterrupt:
        err.print(escape(_unfinished("interrupted", out, run[0] if run else None, previous)), soft_wrap=True)
        return 130
    except (RuntimeError, ValueError) as e:
        err.print(f"[bold red]error:[/] {escape(str(e))}", soft_wrap=True)
    except Exception:
        err.print_exception()
    finally:
        if in_main_thread:
            signal.signal(signal.SIGTERM, old_term)
    if run:
        err.print(escape(_unfinished("stopped", out, run[0], previous)), soft_wrap=True)
    return 2


def _raise_interrupt(signum: int, frame) -> None:
    raise KeyboardInterrupt(signal.Signals(signum).name)


if __name__ == "__main__":
    sys.exit(main())
