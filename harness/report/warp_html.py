"""The warp conformance matrix as an HTML page, with histogram heat maps per warp."""
from __future__ import annotations

import base64
import html

from harness.report.heatmaps import warp_heatmaps_png
from harness.report.style import CSS
from harness.warps import CHECK_NAMES, WarpResult


def _cell(passed: bool | None, text: str) -> str:
    cls = {True: "pass", False: "fail", None: "na"}[passed]
    word = {True: "PASS", False: "FAIL", None: "n/a"}[passed]
    return f'<td class="{cls}">{word}<br><small>{html.escape(text)}</small></td>'


def _summary_table(results: list[WarpResult]) -> str:
    head = "".join(f"<th>{html.escape(n)}</th>" for n in ("warp", *CHECK_NAMES, "overall"))
    rows = []
    for r in results:
        cells = []
        for name in CHECK_NAMES:
            c = r.checks.get(name)
            cells.append(_cell(None, c.summary if c else "") if c is None or c.skipped else _cell(c.passed, c.summary))
        anchor = html.escape(r.label.replace(" ", "_"))
        rows.append(f'<tr><td><a href="#{anchor}">{html.escape(r.label)}</a></td>{"".join(cells)}'
                    f'{_cell(r.passed, "")}</tr>')
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _section(r: WarpResult, reproduce: str, data_file: str | None) -> str:
    png = warp_heatmaps_png(r.observed, r.expected, r.reference_observed, r.domain, r.label)
    img = base64.b64encode(png).decode()
    rows = "".join(
        f"<tr><td>{html.escape(name)}</td>"
        + (_cell(None, c.summary) if c.skipped else _cell(c.passed, c.summary))
        + f"<td><small>{html.escape(_details(c.to_json()))}</small></td></tr>"
        for name, c in r.checks.items())
    extra = ""
    if not r.passed:
        extra = f"<p>Reproduce: <code>{html.escape(reproduce)}</code>"
        if data_file:
            extra += f"; histograms and failing data: <code>{html.escape(data_file)}</code>"
        extra += "</p>"
    anchor = html.escape(r.label.replace(" ", "_"))
    verdict = "PASS" if r.passed else "FAIL"
    return (f'<h2 id="{anchor}">{html.escape(r.label)} — {verdict}</h2>'
            f'<p class="meta">domain {html.escape(r.domain)}, seed {r.seed}, {r.seconds:.2f} s</p>{extra}'
            f'<img alt="histograms of {html.escape(r.label)}" src="data:image/png;base64,{img}">'
            f"<table><tr><th>check</th><th>verdict</th><th>details</th></tr>{rows}</table>")


def _details(d: dict) -> str:
    skip = {"pass", "summary", "figure"}
    parts = []
    for k, v in d.items():
        if k in skip:
            continue
        parts.append(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}")
    return ", ".join(parts)


def warp_report_html(results: list[WarpResult], level: float, meta: dict, reproduce: dict[str, str],
                     data_files: dict[str, str]) -> str:
    """The whole page; failing warps first. `reproduce` and `data_files` are keyed by result label."""
    ordered = sorted(results, key=lambda r: r.passed)
    failed = sum(not r.passed for r in results)
    meta_html = "".join(f"<li>{html.escape(str(k))}: {html.escape(str(v))}</li>" for k, v in meta.items())
    sections = "".join(_section(r, reproduce[r.label], data_files.get(r.label)) for r in ordered)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>mcval warp conformance</title><style>{CSS}</style></head>
<body><h1>Warp conformance: {len(results) - failed} of {len(results)} warps pass</h1>
<ul class="meta">{meta_html}<li>per-test significance level: {level:.3g} (Sidak, family-wise 0.01)</li></ul>
<p>Histograms are over each domain's parameter square (odd resolution); expected counts integrate the pdf
adaptively over every cell. Residual panels show (O−E)/√E: a correct warp is noise; structure there is a bug.</p>
{_summary_table(results)}
{sections}
</body></html>
"""
