"""The calibration as a terminal table: observed false-alarm rates beside their nominal levels."""
from __future__ import annotations

from rich.table import Table

from harness.statistics.calibration_rates import CALIBRATION_LEVELS


def calibration_table(cal) -> Table:
    """Pooled rows first, then each warp; red where the nominal level lies outside the interval."""
    table = Table(title="False-alarm rates of the warp checks (observed, simultaneous 95 % interval)",
                  header_style="bold")
    for col in ("warp", "check", "tests", *[f"at {level:g}" for level in CALIBRATION_LEVELS], "KS p"):
        table.add_column(col)
    for e in cal.pooled + cal.entries:
        cells = [f"[{'green' if r.within else 'red'}]{r.observed:.3f}[/] ({r.low:.2f}-{r.high:.2f})" for r in e.rates]
        table.add_row(e.warp, e.check, str(len(e.p_values)), *cells, f"{e.uniformity:.2g}")
    return table
