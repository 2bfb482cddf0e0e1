"""What the invariance run says: verdict lines (our failures), findings (the reference's breaks), the breaks
float32 explains, and the `invariance` block of results.json."""
from __future__ import annotations

from harness.invariance.check import Cell
from harness.invariance.suite import suite_entries
from harness.invariance.variants import INVARIANCES, TRANSLATION_REACH

REFERENCE_NOTE = "A reference engine's break is a finding about it (BREAKS), never a failure of ours."


def _variant_text(cell: Cell) -> str:
    parts = []
    for v in cell.failing:
        what = v.error or (f"failed at {', '.join(v.comparison.failed_checks)}" if v.comparison else "failed")
        parts.append(f"{v.variant.label}: mean ratio {v.ratio:.4f} ({what})")
    return "; ".join(parts) or (cell.base_error or "")


def failure_lines(cells: list[Cell], engine: str) -> list[str]:
    """One line per failed cell of the gating engine: `sphere_plane:ao scale x0.001: mean ratio 0.9895 (...)`."""
    return [f"{c.case.key} {c.invariance}: {c.base_error or _variant_text(c)}"
            for c in cells if c.engine == engine and not c.passed]


def finding_lines(cells: list[Cell], engine: str) -> list[str]:
    """One line per broken cell of another engine: `reference mitsuba breaks scale on crevice:ao: ...`."""
    return [f"reference {c.engine} breaks {c.invariance} on {c.case.key}: {c.base_error or _variant_text(c)}"
            for c in cells if c.engine != engine and not c.passed]


def float32_lines(cells: list[Cell]) -> list[str]:
    """One line per variant that broke on a scene float32 cannot represent, with the reason in numbers."""
    return [f"{c.engine} {c.case.key} {c.invariance} {v.variant.label}: {v.float32_limit}"
            for c in cells for v in c.beyond_float32]


def invariance_payload(cells: list[Cell], alpha: float, engine: str, meta: dict) -> dict:
    """results.json's `invariance`: pass (ours only), every cell, the findings about the references."""
    ours = [c for c in cells if c.engine == engine]
    return {"pass": all(c.passed for c in ours), "gating_engine": engine, "alpha": alpha,
            "invariances": {i.name: {"summary": i.summary, "variants": [v.label for v in i.variants],
                                     "integrators": [e.name for e in suite_entries() if i.applies_to(e)]}
                            for i in INVARIANCES},
            "cells": [c.to_json() for c in cells], "failures": failure_lines(cells, engine),
            "findings": finding_lines(cells, engine), "float32_limits": float32_lines(cells),
            "translation_reach": TRANSLATION_REACH, "meta": meta}
