"""The BSDF matrix as an HTML page: a table of every BSDF and incident angle, then per row the sampled directions'
histogram beside the pdf's prediction, Mitsuba's samples and the residuals, and every check with its figures."""
from __future__ import annotations

import base64
import html

from harness.bsdfs.evaluate import ALL_CHECKS
from harness.bsdfs.suite import BsdfRow
from harness.report.heatmaps import warp_heatmaps_png
from harness.report.style import CSS
from harness.report.warp_html import WARN_CSS, details_text, verdict_cell


def _anchor(row: BsdfRow) -> str:
    return html.escape(f"{row.label} {row.theta:g}".replace(" ", "_") if row.theta is not None else row.label)


def _title(row: BsdfRow) -> str:
    return row.label + ("" if row.theta is None else f" at {row.theta:g}°")


def _summary_table(rows: list[BsdfRow]) -> str:
    head = "".join(f"<th>{html.escape(n)}</th>" for n in ("BSDF", "θi", *ALL_CHECKS))
    lines = []
    for row in rows:
        theta = "" if row.theta is None else f"{row.theta:g}"
        if row.failure:
            cells = f'<td class="fail" colspan="{len(ALL_CHECKS)}">{html.escape(row.failure)}</td>'
        else:
            cells = "".join(verdict_cell(row.checks[k].verdict, "") if k in row.checks else verdict_cell(None, "", "–")
                            for k in ALL_CHECKS)
        lines.append(f'<tr><td><a href="#{_anchor(row)}">{html.escape(row.label)}</a></td><td>{theta}</td>{cells}</tr>')
    return f"<table><tr>{head}</tr>{''.join(lines)}</table>"


def _section(row: BsdfRow) -> str:
    word = "PASS" if row.passed else "FAIL"
    head = f'<h2 id="{_anchor(row)}">{html.escape(_title(row))} — {word}</h2>'
    if row.failure:
        return head + f'<p class="fail">{html.escape(row.failure)}</p>'
    h = row.histograms
    picture = ""
    if "observed" in h:
        png = warp_heatmaps_png(h["observed"], h["expected"], h.get("reference"), "sphere", _title(row))
        picture = (f'<img alt="sampled directions of {html.escape(_title(row))}" '
                   f'src="data:image/png;base64,{base64.b64encode(png).decode()}">')
    else:
        picture = "<p>No histogram: every sample is on a delta lobe or failed.</p>"
    checks = "".join(f"<tr><td>{html.escape(name)}</td>{verdict_cell(c.verdict, c.summary)}"
                     f"<td><small>{html.escape(details_text(c.to_json()))}</small></td></tr>"
                     for name, c in row.checks.items())
    return (head + f'<p class="meta">{row.seconds:.2f} s</p>{picture}'
            f"<table><tr><th>check</th><th>verdict</th><th>details</th></tr>{checks}</table>")


def bsdf_report_html(rows: list[BsdfRow], level: float, meta: dict) -> str:
    """The whole page, failed rows first."""
    ordered = sorted(rows, key=lambda r: r.passed)
    passed = sum(r.passed for r in rows)
    meta_html = "".join(f"<li>{html.escape(str(k))}: {html.escape(str(v))}</li>" for k, v in meta.items())
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>mcval BSDF matrix</title><style>{CSS}{WARN_CSS}</style></head>
<body><h1>BSDF matrix: {passed} of {len(rows)} rows pass</h1>
<ul class="meta">{meta_html}<li>per-test significance level: {level:.3g} (Sidak over the run's statistical checks)</li></ul>
<p>Each row is one BSDF at one incident direction wi (its polar angle θi; beyond 90° wi is below the surface).
Histograms are of the directions drawn from a density, over the sphere's parameter square ((cos θ+1)/2, φ/2π) in
cells of about equal expected count: the edges are quantiles of a pilot draw's marginals (taken apart on each side
of the horizon) and every cell is drawn the same size, so a correct sampler's expected panel is flat and its residual panel, (O−E)/√E, is noise. Samples on a
delta lobe and failed ones are counted apart (docs/bsdfs.md). "–": the check does not apply to that row.</p>
{_summary_table(rows)}
{"".join(_section(r) for r in ordered)}
</body></html>
"""
