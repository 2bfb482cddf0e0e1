"""The invariance matrix for the terminal: rows scene:integrator, columns invariances, one table per engine."""
from __future__ import annotations

from rich import box
from rich.markup import escape
from rich.table import Table

from harness.invariance.cell import Cell
from harness.invariance.findings import REFERENCE_NOTE


def _cell_text(cell: Cell | None, gating: bool) -> str:
    """PASS or FAIL with the image-mean ratio furthest from 1; a reference engine's break is a finding (yellow)."""
    if cell is None:
        return "[dim]—[/]"
    if cell.base_error:
        return "[bold red]ERR[/]" if gating else "[yellow]ERR[/]"
    if cell.dependence:
        return "[bold red]FAIL[/] batches" if gating else "[yellow]BREAKS[/] batches"
    if cell.status == "inconclusive":
        return "[yellow]INCONCLUSIVE[/]"
    if cell.status == "float32":
        return "[cyan]FLOAT32[/] " + " ".join(escape(v.variant.label) for v in cell.beyond_float32)
    if cell.passed:
        ratio = cell.worst_ratio
        return f"[green]PASS[/] {ratio:.4f}" if ratio == ratio else "[green]PASS[/]"
    failing = " ".join(f"{escape(v.variant.label)}:{v.ratio:.4f}" if v.ratio == v.ratio
                       else f"{escape(v.variant.label)}:no image" for v in cell.failing)
    return f"{'[bold red]FAIL[/]' if gating else '[yellow]BREAKS[/]'} {failing}"


def invariance_tables(cells: list[Cell], alpha: float, gating_engine: str) -> list[Table]:
    """One table per engine (the tested one first): rows scene:integrator, a column per invariance; none without
    cells."""
    if not cells:
        return []
    engines = list(dict.fromkeys(c.engine for c in cells))
    rows = list(dict.fromkeys(c.case.key for c in cells))
    found = {(c.engine, c.invariance, c.case.key): c for c in cells}
    tables = []
    for engine in engines:
        gating = engine == gating_engine
        columns = list(dict.fromkeys(c.invariance for c in cells if c.engine == engine))
        role = "under test: a FAIL fails the run" if gating else "reference: a break is a finding about it"
        table = Table(title=f"Invariances of {engine} ({role}; per-comparison α {alpha:.2g}, family-wise 0.01)",
                      box=box.SIMPLE_HEAD, padding=(0, 1), header_style="bold")
        table.add_column("scene:integrator", no_wrap=True)
        for inv in columns:
            table.add_column(inv, overflow="fold")
        for key in rows:
            table.add_row(escape(key), *[_cell_text(found.get((engine, i, key)), gating) for i in columns])
        tables.append(table)
    tables[-1].caption = ("ratio: the transformed image's mean, mapped back by the expected factor, over the "
                          "base's (furthest from 1 over the variants; mean |n| for normals); after FAIL or "
                          "BREAKS each failing variant with its ratio (no image: the render failed, the reason is below); "
                          "FLOAT32: those variants broke on a scene float32 cannot represent (why, in numbers, below); "
                          "batches: the base's batches are one image where the estimator has noise (below); "
                          "INCONCLUSIVE: the base render is all 0, which no rewrite changes: not judged; "
                          f"—: not applicable. {REFERENCE_NOTE}")
    return tables
