"""Power figures of the warp checks (see harness.warps.power) as short texts for the terminal and the page."""
from __future__ import annotations

import html

from harness.warps.check_result import CheckResult
from harness.warps.evaluate import WarpResult

#: What each defect is called after its figure.
_UNITS = {"pdf_half": "pdf", "mass_moved": "mass", "normalisation": "∫", "pdf_relative": "rel."}


def percent(x: float) -> str:
    """A fraction as a percentage with two significant digits: 0.0095 -> "0.95%", 0.019 -> "1.9%"."""
    return f"{x * 100:.2g}%" if x * 100 < 10 else f"{x * 100:.0f}%"


def _figures(c: CheckResult | None) -> list[dict]:
    return [] if c is None or c.skipped else list(c.details.get("power", []))


def figure_text(f: dict) -> str:
    """One figure, e.g. "≥1.9% pdf"; "—" with no number (none applies, or nothing detected up to 100%)."""
    x = f.get("detects_90")
    if x is None:
        return "—"
    return f"≥{percent(x)} {_UNITS.get(f.get('defect', ''), '')}".rstrip()


def figure_tooltip(f: dict) -> str:
    """What the defect is, and how the figure was found."""
    how = (f"smallest detected in {f.get('power_at_figure', 0.9):.0%} of {f['replications']} simulated runs"
           if f.get("method") == "simulation" else "exact, by construction of the check")
    return f"{f.get('description', '')} ({how})"


def power_cell(r: WarpResult) -> str:
    """The matrix's power column: "χ² 1.9%/0.95% mi 1.3%" (pdf error / mass moved; mass moved), or "—"."""
    chi2 = {f["defect"]: f.get("detects_90") for f in _figures(r.checks.get("chi2"))}
    homog = [f.get("detects_90") for f in _figures(r.checks.get("samples_vs_mitsuba"))]
    parts = []
    if chi2:
        parts.append("χ² " + "/".join(percent(chi2[k]) if chi2.get(k) is not None else "—"
                                      for k in ("pdf_half", "mass_moved") if k in chi2))
    if homog:
        parts.append("mi " + (percent(homog[0]) if homog[0] is not None else "—"))
    return " ".join(parts) or "—"


POWER_CAPTION = ("power: the smallest defect detected 90% of the time at this budget and level — χ²: pdf "
                 "error on half of the mass / fraction of samples moved between halves; mi: samples moved, "
                 "homogeneity test against Mitsuba")


def power_html(c: CheckResult | None) -> str:
    """A check's figures as HTML, each with its defect in a tooltip."""
    figures = _figures(c)
    if not figures:
        return ""
    return ", ".join(f'<span title="{html.escape(figure_tooltip(f))}">detects {html.escape(figure_text(f))}</span>'
                     if f.get("detects_90") is not None else
                     f'<span title="{html.escape(figure_tooltip(f))}">{html.escape(f.get("description", "—"))}</span>'
                     for f in figures)
