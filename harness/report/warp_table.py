"""The warp conformance matrix as a rich table for the terminal."""
from __future__ import annotations

from rich import box
from rich.table import Table

from harness.report.warp_power_text import POWER_CAPTION, power_cell
from harness.warps.check_result import CheckResult
from harness.warps.evaluate import CHECK_NAMES, WarpResult, format_params

#: Column headers, short enough for an 80-column terminal.
_HEADERS = {"chi2": "χ² p", "normalisation": "∫pdf", "domain": "bad", "pdf_vs_target": "pdf≈tgt",
            "samples_vs_target": "smp≈tgt", "pdf_vs_mitsuba": "pdf≈mi", "samples_vs_mitsuba": "smp≈mi",
            "hard_inputs": "NaN", "throughput": "M/s (mi, ×)"}


def _figure(name: str, c: CheckResult) -> str:
    """The check's headline number, in a few characters."""
    f = c.figure
    if c.not_judged:
        return "not judged"
    if name in ("chi2", "samples_vs_target", "samples_vs_mitsuba"):
        return f"{f:.2f}" if f >= 0.01 else f"{f:.0e}"
    if name == "normalisation":
        return f"{f:.4f}"
    if name in ("pdf_vs_target", "pdf_vs_mitsuba"):
        if "factor" in c.details:  # a named constant factor says more than its relative difference
            return f"×{c.details['factor']}"
        return f"{c.details.get('max_relative_difference', f):.0e}"
    if name == "throughput":
        ref, ratio = c.details.get("reference_samples_per_second"), c.details.get("ratio")
        return f"{f / 1e6:.0f}" + (f" ({ref / 1e6:.0f}, {ratio:.2f}×)" if ref and ratio else "")
    return f"{int(f)}"


def verdict_text(passed: bool | None) -> str:
    return {True: "[green]PASS[/]", False: "[bold red]FAIL[/]", None: "[dim]—[/]"}[passed]


#: Rich styles of check verdicts: a check that passed with warnings is yellow.
_STYLES = {"PASS": "green", "WARN": "yellow", "FAIL": "bold red"}


def warp_verdict_text(r: WarpResult) -> str:
    """PASS, PASS (n warnings) in yellow, or FAIL."""
    if r.verdict == "WARN":
        return f"[yellow]PASS ({r.warnings} warning{'s' if r.warnings > 1 else ''})[/]"
    return verdict_text(r.passed)


def warp_table(results: list[WarpResult], level: float) -> Table:
    """One row per warp, one column per check: verdict and figure."""
    table = Table(title=f"Warp conformance (per-test level {level:.2g}, Sidak over the run)", header_style="bold",
                  box=box.SIMPLE_HEAD, padding=(0, 1))
    table.add_column("warp", no_wrap=True)
    for name in CHECK_NAMES:
        table.add_column(_HEADERS[name], no_wrap=True)
    table.add_column("power", no_wrap=True)
    table.add_column("all", no_wrap=True)
    for r in results:
        cells = []
        for name in CHECK_NAMES:
            c = r.checks.get(name)
            if c is None or c.skipped:
                cells.append("[dim]n/a[/]")
            else:
                color = _STYLES.get(c.verdict or "", "dim")
                cells.append(f"[{color}]{_figure(name, c)}[/]")
        label = r.warp.removeprefix("square_to_")
        if isinstance(r.params, dict):
            label += " " + " ".join(f"{'α' if k == 'alpha' else k}={v:g}" for k, v in r.params.items())
        elif r.params is not None:
            label += f" {format_params(r.params)}"
        table.add_row(label, *cells, power_cell(r), warp_verdict_text(r))
    table.caption = ("green pass, yellow pass with warnings (listed in warps.html), red fail. χ² p, smp≈tgt, smp≈mi: "
                     "p-values; ∫pdf: integral; bad: domain violations; pdf≈tgt, pdf≈mi: max rel. diff; tgt: the "
                     "closed form the warp's name promises (n/a: a name mcval does not know); NaN: NaN/Inf on "
                     "hard inputs in [0,1); M/s: tested (reference, tested ÷ reference: median of interleaved pairs); " + POWER_CAPTION)
    return table
