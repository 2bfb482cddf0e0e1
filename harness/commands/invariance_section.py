"""The invariances as a section of a run (`invariance`, `validate`): each engine against itself under every
transformation; only the tested engine's breaks fail, a reference's are findings."""
from __future__ import annotations

import time
from pathlib import Path

from rich.markup import escape

from harness.commands.output import console, task_progress
from harness.results import write_atomic
from harness.verdict import Tally


def run_invariance_section(args, only, run_dir: Path, executor, engines=None) -> tuple[Tally, dict]:
    """Returns (what was judged of the tested engine's cells, the results.json block); writes invariance.html."""
    from harness.engines.registry import make_engine
    from harness.images.references import REFERENCE_SEED
    from harness.invariance.check import family_alpha, run_invariances
    from harness.invariance.stored import stored_cells
    from harness.statistics.constants import IMAGE_BATCHES
    from harness.images.judged import why_no_cases
    from harness.images.suite import not_applicable_cases
    from harness.invariance.findings import failure_lines, invariance_payload, invariance_tally, not_judged_lines
    from harness.invariance.suite import select
    from harness.report.invariance_html import invariance_html
    from harness.report.invariance_table import invariance_tables

    from harness.commands.options import case_selection
    from harness.report.reproduce import invocation, reproduce_line

    selection = case_selection(args)
    cases, invariances = select(only, **selection)
    sources = {u.prepared: str(u.source) for u in selection["user"] or ()}
    if engines is None:
        engines = [make_engine(args.engine)]
        if not getattr(args, "no_mitsuba", False):
            engines.append(make_engine(args.reference, variant=args.variant))
    gating = engines[0].name
    start = time.perf_counter()
    # A reference engine's cells do not depend on the renderer under test: rendered at the references' seed,
    # and read from references/ where stored for exactly this check (harness/invariance/stored.py).
    references, alpha = engines[1:], family_alpha(cases, invariances)
    known, misses = {}, []
    if references and getattr(args, "reference_live", False):
        misses = ["asked for by --reference-live"]
    elif references:
        known, misses = stored_cells(references, cases, invariances, alpha, IMAGE_BATCHES)
    with task_progress("invariances", executor) as show:
        cells, _ = run_invariances(engines, cases, invariances, args.seed, on_status=show, executor=executor,
                                   seeds={e.name: REFERENCE_SEED for e in references}, known=known, alpha=alpha)
    seconds = time.perf_counter() - start
    for table in invariance_tables(cells, alpha, gating):
        console.print(table)
    meta = {"engines": [e.version() for e in engines], "seed": args.seed, "seconds": round(seconds, 1),
            "reference_seed": REFERENCE_SEED, "reference_cells": reference_sources(references, cases, known, misses)}
    for line in meta["reference_cells"]["lines"]:
        console.print(escape(line), soft_wrap=True)
    none = "" if cells else why_no_cases(gating, selection["integrators"], not_applicable_cases(None, **selection))
    payload = invariance_payload(cells, alpha, gating, meta, none)
    tally = invariance_tally(cells, gating, none)
    write_atomic(run_dir / "invariance.html", invariance_html(payload))
    for line in payload["findings"]:
        console.print(f"[yellow]finding[/] {escape(line)}", soft_wrap=True)
    for line in payload["float32_limits"]:
        console.print(f"[cyan]float32[/] {escape(line)}", soft_wrap=True)
    tested = [c for c in cells if c.engine == gating]
    beyond = sum(c.status == "float32" for c in tested)
    unjudged = len(tested) - tally.judged
    console.print(f"{tally.passed - beyond} of {len(tested)} invariance checks of {gating} pass"
                  + (f", {beyond} broke only where float32 cannot represent the scene" if beyond else "")
                  + (f", {unjudged} not judged" if unjudged else "") + f", in {seconds:.1f} s.")
    for line in failure_lines(cells, gating):
        console.print(f"[red]FAIL[/] invariance {escape(line)}", soft_wrap=True)
    for line in not_judged_lines(cells, gating):
        console.print(f"[yellow]not judged[/] {escape(line)}", soft_wrap=True)
    run = invocation(args)
    for c in (c for c in tested if c.status == "fail"):
        console.print("  reproduce: " + escape(reproduce_line("invariance", ["--only", c.case.key, c.invariance],
                                                              args.seed, run, sources.get(c.case.scene, ""))),
                      soft_wrap=True)
    console.print(f"Page: {run_dir / 'invariance.html'}")
    return tally, payload


def reference_sources(references, cases, known: dict, misses: list[str]) -> dict:
    """Where each reference engine's cells came from: how many stored, how many rendered now and why."""
    lines = []
    for engine in references:
        stored = sum((engine.name, c.key) in known for c in cases)
        line = (f"{engine.name}: {stored} of {len(cases)} cases' cells read from references/{engine.name} "
                f"(stored with their provenance by `make references`)")
        lines.append(line if stored else f"{engine.name}: every case rendered now")
    if misses:
        shown = misses[:3] + ([f"and {len(misses) - 3} more"] if len(misses) > 3 else [])
        lines.append("rendered now: " + "; ".join(shown))
    return {"stored": len(known), "rendered": len(references) * len(cases) - len(known), "misses": misses,
            "lines": lines}
