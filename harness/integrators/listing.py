"""`python -m harness integrators`: every integrator of the renderer with what the harness knows of it."""
from __future__ import annotations

from rich import box
from rich.markup import escape
from rich.table import Table

from harness.integrators.registry import Matched


def integrators_table(matched: Matched) -> Table:
    """One row per renderer integrator: its entry's file, budgets, Mitsuba mapping, closed form and needs;
    an integrator without an entry says so (it is not validated)."""
    table = Table(title="Integrators: the renderer's registry and the harness's entries", box=box.SIMPLE_HEAD,
                  header_style="bold", padding=(0, 1), expand=True)
    for name in ("integrator", "entry", "spp ours", "spp ref."):
        table.add_column(name, no_wrap=True)
    table.add_column("Mitsuba", ratio=3, overflow="fold")
    table.add_column("closed form", ratio=2, overflow="fold")
    table.add_column("needs", ratio=1, overflow="fold")
    for e in matched.entries:
        needs = ", ".join(summary for summary, _ in e.requirements) or "-"
        table.add_row(e.name, escape(e.source), str(e.our_spp), str(e.reference_spp), escape(e.mitsuba.summary().replace("; ", "\n")),
                      escape(e.analytic.summary) if e.analytic else "none", escape(needs))
    for name in matched.without_entry:
        table.add_row(name, "[yellow]no harness entry[/]", "", "", "", "", "")
    return table
