"""What the invariance run says: verdict lines (our failures), the cells not judged and why, findings (the
reference's breaks), the breaks float32 explains, the tally of what was judged, and the `invariance` block of
results.json."""
from __future__ import annotations

from harness.invariance.cell import Cell
from harness.invariance.suite import suite_entries
from harness.invariance.variants import INVARIANCES, TRANSLATION_REACH
from harness.verdict import Tally, Verdict, run_verdict

REFERENCE_NOTE = "A reference engine's break is a finding about it (BREAKS), never a failure of the tested engine."


def _variant_text(cell: Cell) -> str:
    parts = []
    for v in cell.failing:
        what = v.error or v.dependence or (f"failed at {', '.join(v.comparison.failed_checks)}" if v.comparison
                                          else "failed")
        parts.append(f"{v.variant.label}: mean ratio {v.ratio:.4f} ({what})")
    return "; ".join(parts)


def _base_text(cell: Cell) -> str | None:
    """Why the cell fails whatever its variants say (no base image, base batches not independent), or None."""
    return cell.base_error or cell.dependence


def _grouped(cells: list[Cell], text) -> list[str]:
    """`key invariance: text` per cell, except that cells of one case failing for one reason about their base
    share a line: `key (scale, rotate): reason`, so the cause leads, once."""
    lines: dict[tuple[str, str], list[str]] = {}
    out: list[str | tuple[str, str]] = []
    for c in cells:
        base = _base_text(c)
        if base is None:
            out.append(f"{c.case.key} {c.invariance}: {text(c)}")
            continue
        if (c.case.key, base) not in lines:
            lines[(c.case.key, base)] = []
            out.append((c.case.key, base))
        lines[(c.case.key, base)].append(c.invariance)
    return [o if isinstance(o, str) else f"{o[0]} ({', '.join(lines[o])}): {o[1]}" for o in out]


def failure_lines(cells: list[Cell], engine: str) -> list[str]:
    """One line per failed cell of the gating engine: `sphere_plane:ao scale x0.001: mean ratio 0.9895 (...)`;
    one per case where the cells fail for their base: `plane_point:ao (scale, rotate): batches not ...`."""
    return _grouped([c for c in cells if c.engine == engine and c.status == "fail"], _variant_text)


def finding_lines(cells: list[Cell], engine: str) -> list[str]:
    """One line per broken cell of another engine: `reference mitsuba breaks scale on crevice:ao: ...`."""
    return [f"reference {c.engine} breaks {c.invariance} on {c.case.key}: {_base_text(c) or _variant_text(c)}"
            for c in cells if c.engine != engine and c.status == "fail"]


def not_judged_lines(cells: list[Cell], engine: str) -> list[str]:
    """One line per reason cells of `engine` were not judged: `3 cells (plane_point:ao scale, ...): reason`."""
    by_reason: dict[str, list[str]] = {}
    for c in cells:
        if c.engine == engine and c.not_judged:
            by_reason.setdefault(c.not_judged, []).append(f"{c.case.key} {c.invariance}")
    return [f"{len(keys)} cell{'s' if len(keys) > 1 else ''} ({', '.join(keys[:3])}"
            f"{f' and {len(keys) - 3} more' if len(keys) > 3 else ''}): {reason}" for reason, keys in by_reason.items()]


def float32_lines(cells: list[Cell]) -> list[str]:
    """One line per variant that broke on a scene float32 cannot represent, with the reason in numbers."""
    return [f"{c.engine} {c.case.key} {c.invariance} {v.variant.label}: {v.float32_limit}"
            for c in cells for v in c.beyond_float32]


def invariance_tally(cells: list[Cell], engine: str, no_cells: str = "") -> Tally:
    """What the run judged of `engine`'s cells: passed (float32 breaks included), failed, and why the rest were
    not judged (or, `no_cells`, why there were none)."""
    tested = [c for c in cells if c.engine == engine]
    reasons = tuple(not_judged_lines(cells, engine)) if tested else (no_cells or "no case applies",)
    return Tally(f"invariance cells of {engine}", sum(c.passed for c in tested), sum(c.status == "fail" for c in tested),
                 reasons)


def invariance_payload(cells: list[Cell], alpha: float, engine: str, meta: dict, no_cells: str = "") -> dict:
    """results.json's `invariance`: pass (the tested engine's cells only: something judged, nothing failed),
    what was judged, every cell, the findings about the references. `no_cells`: why there are no cells, if
    there are none."""
    tally = invariance_tally(cells, engine, no_cells)
    verdict, reason = run_verdict([tally])
    return {"pass": verdict is Verdict.PASS, "verdict": verdict.value, "verdict_reason": reason,
            "judged": tally.to_json(), "gating_engine": engine, "alpha": alpha,
            "invariances": {i.name: {"summary": i.summary, "variants": [v.label for v in i.variants],
                                     "integrators": [e.name for e in suite_entries() if i.applies_to(e)]}
                            for i in INVARIANCES},
            "cells": [c.to_json() for c in cells], "failures": failure_lines(cells, engine),
            "not_judged": not_judged_lines(cells, engine), "findings": finding_lines(cells, engine),
            "float32_limits": float32_lines(cells), "translation_reach": TRANSLATION_REACH, "meta": meta}
