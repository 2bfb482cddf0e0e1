"""The calibration as a terminal table: observed false-alarm rates beside their nominal levels."""
from __future__ import annotations

from rich.table import Table

from harness.report.verdict_style import VERDICT_COLOUR, VERDICT_KEY
from harness.statistics.calibration_rates import CALIBRATION_LEVELS


def calibration_table(cal, what: str = "warp") -> Table:
    """Pooled rows first, then each warp (or BSDF row: `what`); green where the nominal level lies inside the
    interval, yellow where the interval lies below it (conservative), red above it (liberal)."""
    table = Table(title=f"False-alarm rates of the {what} checks (observed, simultaneous 95 % interval)",
                  header_style="bold", caption=VERDICT_KEY)
    for col in (what, "check", "tests", *[f"at {level:g}" for level in CALIBRATION_LEVELS], "KS p"):
        table.add_column(col)
    for e in cal.pooled + cal.entries:
        cells = [f"[{VERDICT_COLOUR[r.verdict]}]{r.observed:.3f}[/] ({r.low:.2f}-{r.high:.2f})" for r in e.rates]
        table.add_row(e.warp, e.check, str(len(e.p_values)), *cells, f"{e.uniformity:.2g}")
    return table


def image_calibration_table(cal: dict) -> Table:
    """The image calibration's whole-comparison rates per kind, and its power per integrator."""
    table = Table(title="Calibration of the image comparisons (whole comparison; rate \\[interval])",
                  header_style="bold", caption=VERDICT_KEY)
    table.add_column("kind")
    table.add_column("comparisons")
    for level in CALIBRATION_LEVELS:
        table.add_column(f"at {level:g}")
    for kind in dict.fromkeys(b["kind"] for b in cal["blocks"]):
        cells = [b for b in cal["blocks"] if b["kind"] == kind and b["scale"] == "whole"]
        table.add_row(kind, str(cells[0]["comparisons"]), *[
            f"[{VERDICT_COLOUR[b['verdict']]}]{b['false_alarm_rate']:.3f}[/] [{b['interval'][0]:.3f}, "
            f"{b['interval'][1]:.3f}]" for b in cells])
    for integrator, v in cal["power"].items():
        table.add_row(f"power {integrator}", str(v["comparisons"]),
                      f"whole image {bias_text(v['global_bias_90'])}", f"one tile {bias_text(v['tile_bias_90'])}", "")
    return table


def bias_text(b: float | None) -> str:
    """A power figure: the smallest bias found often enough, or that none up to the largest planted was."""
    from harness.images.null_task import BIASES
    return f"beyond {BIASES[-1]:g}" if b is None else f"{b:.2g}"


def bsdf_power_table(cal) -> Table:
    """The BSDF calibration's planted defects: found how often, beside the power the check states."""
    table = Table(title="Power of the BSDF checks: defects of the stated size, planted", header_style="bold")
    for col in ("check", "planted defect", "level", "stated", "found [interval]"):
        table.add_column(col)
    for p in cal.power:
        colour = "green" if p.holds else "red"
        table.add_row(p.check, p.defect, "" if p.level is None else f"{p.level:g}", f"{p.stated:.0%}",
                      f"[{colour}]{p.found} of {p.runs}[/] [{p.low:.3f}, {p.high:.3f}]")
    return table
