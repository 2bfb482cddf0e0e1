"""`mcval integrators`: every integrator of the renderer with what the harness knows of it."""
from __future__ import annotations

from rich import box
from rich.markup import escape
from rich.table import Table

from harness.engines.base import Engine
from harness.integrators.registry import Matched


def integrators_table(matched: Matched, reference: Engine) -> Table:
    """One row per integrator of the tested engine: its entry's file, budgets, how the `reference` engine
    renders it (Engine.integrator_mapping), closed form and needs; an integrator without an entry says so (it is
    not validated)."""
    table = Table(title="Integrators: the renderer's registry and the harness's entries", box=box.SIMPLE_HEAD,
                  header_style="bold", padding=(0, 1),
                  caption="spp: samples per pixel per batch, the tested engine's / the stored references'")
    for name in ("integrator", "entry", "spp"):
        table.add_column(name, no_wrap=True)
    table.add_column(f"{reference.name} renders it as", overflow="fold", min_width=26)
    table.add_column("closed form", overflow="fold", max_width=18)
    table.add_column("needs", overflow="fold", min_width=13)
    for e in matched.entries:
        needs = ", ".join(summary for summary, _ in e.requirements) or "-"
        # The plugin, then one line per change to the scene.
        mapping = (reference.integrator_mapping(e.name) or "not rendered").replace("; ", "\n")
        table.add_row(e.name, escape(e.source), f"{e.tested_spp}/{e.reference_spp}", escape(mapping),
                      escape(e.analytic.summary) if e.analytic else "none", escape(needs))
    for name in matched.without_entry:
        table.add_row(name, "[yellow]no harness entry[/]", "", "", "", "")
    return table
