"""The command line: `python -m harness {warps,validate}`. The only module that prints."""
from __future__ import annotations

import argparse
import platform
import sys
import time
from pathlib import Path

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from harness.results import new_run_dir, write_atomic, write_json
from harness.stats import WARP_SAMPLES

# Logs (CI, pipes) get a wide table rather than a truncated one.
console = Console(width=None if sys.stdout.isatty() else 120)
err = Console(stderr=True)


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m harness",
        description="mcval: validate a Monte Carlo renderer against its pdfs and against Mitsuba 3.",
        epilog="Each command writes results/<run>/ (results.json, HTML pages) and exits 1 if any check fails.")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def common(q: argparse.ArgumentParser) -> None:
        q.add_argument("--out", type=Path, default=Path("results"), help="folder for run folders (default: results)")
        q.add_argument("--seed", type=int, default=0, help="seed of every random choice (default: 0)")

    w = sub.add_parser("warps", help="the warp conformance matrix alone",
                       description="Check every warp of the renderer against its pdf (chi-square, normalisation, "
                                   "domain, hard inputs) and against Mitsuba 3's implementation.")
    common(w)
    w.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")
    w.add_argument("--only", nargs="+", metavar="WARP",
                   help="check only these warps, e.g. tent beckmann:0.01 (default: all)")
    w.add_argument("--samples", type=int, default=WARP_SAMPLES,
                   help=f"samples per warp for the statistical tests (default: {WARP_SAMPLES})")
    w.add_argument("--no-mitsuba", action="store_true", help="skip the checks against Mitsuba 3")

    v = sub.add_parser("validate", help="everything: what `make validate` runs",
                       description="Run the whole validation and write results/<run>/report.html.")
    common(v)
    return p


def _run_warps(args, specs, run_dir: Path) -> tuple[bool, dict]:
    from harness.engines.ours import OurEngine
    from harness.report.warp_table import warp_table
    from harness.warp_outputs import warp_payload, write_warp_outputs
    from harness.warp_suite import run_matrix

    ours = OurEngine()
    reference = None
    if not getattr(args, "no_mitsuba", False):
        from harness.engines.mitsuba import MitsubaEngine
        reference = MitsubaEngine()
    samples = getattr(args, "samples", WARP_SAMPLES)
    start = time.perf_counter()
    with Progress(TextColumn("warps"), BarColumn(), MofNCompleteColumn(), TextColumn("{task.description}"),
                  TimeElapsedColumn(), console=err, transient=True) as progress:
        task = progress.add_task("", total=len(specs))
        results, level = run_matrix(ours, reference, specs, seed=args.seed, samples=samples,
                                    on_progress=lambda s: progress.update(task, advance=1, description=s.key))
    seconds = time.perf_counter() - start
    meta = {"engine": ours.version(), "reference": reference.version() if reference else "none",
            "samples per warp": samples, "seed": args.seed, "seconds": round(seconds, 2),
            "machine": f"{platform.machine()}, {platform.system()} {platform.release()}"}
    console.print(warp_table(results, level))
    paths = write_warp_outputs(run_dir, specs, results, level, meta, args.seed)
    payload = warp_payload(results, level, meta)
    failed = [r.label for r in results if not r.passed]
    console.print(f"{len(results) - len(failed)} of {len(results)} warps pass, in {seconds:.1f} s. "
                  f"Page: {paths['html']}")
    for label in failed:
        console.print(f"[red]FAIL[/] {label}: data in {run_dir / 'warps'}")
    return not failed, payload


def _index_html(sections: dict[str, tuple[bool, str]]) -> str:
    from harness.report.style import CSS
    rows = "".join(f'<tr><td><a href="{href}">{name}</a></td><td class="{"pass" if ok else "fail"}">'
                   f'{"PASS" if ok else "FAIL"}</td></tr>' for name, (ok, href) in sections.items())
    return (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>mcval report</title>"
            f"<style>{CSS}</style></head><body><h1>mcval validation report</h1>"
            f"<table><tr><th>section</th><th>verdict</th></tr>{rows}</table></body></html>")


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    from harness.warp_suite import select
    try:
        specs = select(getattr(args, "only", None))
        run_dir = new_run_dir(args.out)
        ok, payload = _run_warps(args, specs, run_dir)
        payload = {"run": run_dir.name, "pass": ok, **{k: v for k, v in payload.items() if k != "pass"}}
        write_json(run_dir / "results.json", payload)
        if args.command == "warps" and args.json:
            write_json(args.json, payload)
        if args.command == "validate":
            write_atomic(run_dir / "report.html", _index_html({"Warp conformance": (ok, "warps.html")}))
        console.print(f"Results: {run_dir / 'results.json'}")
        return 0 if ok else 1
    except (RuntimeError, ValueError) as e:
        err.print(f"[bold red]error:[/] {e}")
        return 2


if __name__ == "__main__":
    sys.exit(main())
