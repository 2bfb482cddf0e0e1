"""The image comparisons as a section of a run (`images`, `validate`): run the cases, print their tables,
write report.html and junit.xml."""
from __future__ import annotations

import time
from pathlib import Path

from rich.markup import escape

from harness.commands.output import console, err, task_progress
from harness.foreign_text import LINE_LIMIT, foreign
from harness.verdict import Tally


def _print_real_scenes(real, not_applicable, alpha: float) -> None:
    """The real scenes under their own heading: their table, then the cases that do not apply and why."""
    from harness.report.image_table import image_table

    console.rule("[bold]Real scenes[/] (scenes/real/)")
    if real:
        table = image_table(real, alpha)
        table.title = f"Real scenes: {table.title}"
        console.print(table)
    for case, reason in not_applicable:
        console.print(f"{escape(case.key)}: not applicable: {escape(reason)} (not run)")


def _print_regression(payload: dict) -> None:
    regression = payload["regression"] or []
    new = [e for e in regression if e["flags"] == ["new case"]]
    if new:
        console.print(f"{len(new)} case(s) new since {payload['baseline']}")
    for entry in regression:
        if entry["flags"] and entry not in new:
            console.print(f"[yellow]changed[/] {entry['scene']}:{entry['integrator']}: {'; '.join(entry['flags'])}")


def _budgeted(cases, tested, reference, target: float, seed: int):
    """The cases with the samples per pixel that find `target` 90 % of the time (harness/images/budget.py), and
    the budgets; each printed, with the whole run's rendering time, before anything is rendered."""
    import dataclasses

    from harness.images.budget import plan_budget
    from harness.images.run import case_seed, closed_forms, comparison_level, strategy_checks

    alpha = comparison_level(cases, closed_forms(cases), strategy_checks(cases, tested))
    budgets, planned = [], []
    for case in cases:
        if case.problem:
            planned.append(case)
            continue
        try:
            budget = plan_budget(case, tested, reference, target, alpha, case_seed(case, seed) + 1)
        except Exception as e:  # the case itself fails in the run, with its own line
            err.print(f"{escape(case.key)}: no budget planned ({escape(foreign(f'{type(e).__name__}: {e}', LINE_LIMIT))}); "
                      "it keeps its default", soft_wrap=True, highlight=False)
            planned.append(case)
            continue
        err.print(escape(budget.line), soft_wrap=True)
        budgets.append(budget)
        planned.append(dataclasses.replace(case, spp=budget.spp) if budget.spp else case)
    err.print(f"--detect-bias {target:.3g}: about {sum(b.seconds for b in budgets):.1f} s of rendering for "
              f"{len(budgets)} case(s); where a target cannot be reached the case keeps its default budget")
    return planned, budgets


def _print_message(message: str) -> None:
    """A case's message: it may quote an engine's error, so bounded and not highlighted (rich's highlighter
    takes minutes over a megabyte of one word)."""
    err.print(f"[yellow]{escape(foreign(message, LINE_LIMIT))}[/]", soft_wrap=True, highlight=False)


#: The run's log of errors no stage foresaw: each failed its case with one line, its traceback is here.
ERRORS_LOG = "errors.log"


def _log_tracebacks(results, run_dir: Path) -> None:
    """Every traceback of the run's cases (an unforeseen error in a case or in preparing its scene) into the
    run's ERRORS_LOG, and one line saying where."""
    from harness.results import write_atomic

    logged = [(r.case.key, r.error, r.traceback or r.case.traceback) for r in results
              if r.traceback or r.case.traceback]
    if logged:
        write_atomic(run_dir / ERRORS_LOG, "".join(f"== {key}: {error}\n{trace}\n" for key, error, trace in logged))
        err.print(f"[yellow]{len(logged)} case(s) failed with an error the harness did not foresee: "
                  f"tracebacks in {escape(str(run_dir / ERRORS_LOG))}[/]", soft_wrap=True)


def engine_meta(role: str, engine) -> dict[str, str]:
    """An engine's provenance for a report's header and results.json: "engine" (its version line) and, for an
    engine file, "engine file" and "engine command"."""
    described = engine.describe()
    meta = {role: f"{described['name']}: {described['version']}"}
    for key in ("file", "command"):
        if key in described:
            meta[f"{role} {key}"] = described[key]
    return meta


def run_image_section(args, cases, run_dir: Path, warps: dict | None, baseline: Path | None,
                      not_applicable=(), invariance: dict | None = None, executor=None,
                      phases: dict[str, float] | None = None) -> tuple[Tally, dict]:
    """Every case against its references; returns (what was judged, the results.json fields). `phases`: the
    run's phases so far (name -> seconds), shown in the report's header."""
    from harness.commands.reference_image_options import reference_image
    from harness.engines.registry import make_engine
    from harness.images.judged import image_tally
    from harness.images.real_scenes import real_scenes_json, split
    from harness.images.run import run_images
    from harness.integrators import entries
    from harness.report.image_html import reproduce_command
    from harness.report.reproduce import invocation
    from harness.report.image_outputs import write_image_outputs
    from harness.report.image_table import image_table

    tested, reference = make_engine(args.engine), make_engine(args.reference, variant=args.variant)
    budgets = []
    if getattr(args, "detect_bias", None) and reference_image(args) is None:
        cases, budgets = _budgeted(cases, tested, reference, args.detect_bias, args.seed)
    start = time.perf_counter()
    with task_progress("images", executor) as show:
        results, alpha = run_images(cases, tested, reference, args.seed, on_status=show,
                                    on_message=_print_message,
                                    executor=executor, reference_image=reference_image(args))
        where = executor.description
    seconds = time.perf_counter() - start
    synthetic, real = split(results)
    if synthetic:
        console.print(image_table(synthetic, alpha))
    if real or not_applicable:
        _print_real_scenes(real, not_applicable, alpha)
    for r in results:
        if r.reference_fit is not None:
            console.print(f"{escape(r.case.key)}: {escape(r.reference_fit.summary)}", soft_wrap=True)
    # An integrator the tested engine renders that the harness has no entry for (in our renderer's registry).
    for name in (n for n in tested.integrators or () if n not in entries()):
        console.print(f"[yellow]{escape(name)}[/]: no harness entry (not validated; see `mcval "
                      "integrators`)")
    run = invocation(args)
    meta = {**engine_meta("engine", tested), **engine_meta("reference", reference), "seed": args.seed,
            "image seconds": round(seconds, 1), "ran on": where}
    if budgets:
        meta["budgets (--detect-bias)"] = "; ".join(b.line for b in budgets)
    if phases:
        meta["phases before the images"] = " · ".join(f"{name} {s:.1f} s" for name, s in phases.items())
    payload = write_image_outputs(run_dir, results, alpha, warps, meta, baseline, invariance, run)
    _log_tracebacks(results, run_dir)
    if real or not_applicable:
        payload["real_scenes"] = real_scenes_json(results, not_applicable)
    _print_regression(payload)
    tally = image_tally(results, not_applicable)
    inconclusive = [r for r in results if r.verdict == "INCONCLUSIVE"]
    console.print(f"{tally.passed} of {len(results)} image comparisons pass"
                  + (f", {len(inconclusive)} inconclusive" if inconclusive else "")
                  + f", in {seconds:.1f} s. Report: {run_dir / 'report.html'}")
    for r in inconclusive:
        console.print(f"[yellow]INCONCLUSIVE[/] {r.case.key} — {escape(r.inconclusive)}", soft_wrap=True)
    for r in (r for r in results if r.failed):
        why = r.why
        console.print(f"[red]FAIL[/] {escape(r.case.key)}{' — ' + escape(foreign(why, LINE_LIMIT)) if why else ''}: "
                      f"{escape(reproduce_command(r, run))}", soft_wrap=True, highlight=False)
    return tally, payload
