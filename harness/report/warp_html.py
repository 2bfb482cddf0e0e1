"""The warp conformance matrix as an HTML page, with histogram heat maps per warp."""
from __future__ import annotations

import base64
import html

from harness.report.heatmaps import warp_heatmaps_png
from harness.report.style import CSS
from harness.report.warp_power_text import POWER_CAPTION, power_cell, power_html
from harness.warps.evaluate import CHECK_NAMES, WarpResult


#: A check that passed with warnings is yellow (the shared stylesheet has pass, fail and na).
WARN_CSS = ".warn { background: #fff3c4; } li.fail { color: #a00; } li.warn { color: #7a5b00; }"
_ORDER = {"FAIL": 0, "WARN": 1, "PASS": 2}


def verdict_cell(verdict: str | None, text: str, word: str | None = None) -> str:
    """A table cell for a verdict ("PASS", "WARN", "FAIL"; anything else: n/a) over a short text."""
    cls = {"PASS": "pass", "WARN": "warn", "FAIL": "fail"}.get(verdict or "", "na")
    word = word or (verdict if cls != "na" else "n/a")
    return f'<td class="{cls}">{word}<br><small>{html.escape(text)}</small></td>'


def _warp_word(r: WarpResult) -> str:
    return f"PASS ({r.warnings} warning{'s' if r.warnings > 1 else ''})" if r.verdict == "WARN" else r.verdict


def _findings(r: WarpResult) -> str:
    """Every finding of every check, failures first, each with its inputs and advice."""
    items = sorted(((name, f) for name, c in r.checks.items() for f in c.findings),
                   key=lambda item: _ORDER[item[1].severity])
    if not items:
        return ""
    lis = "".join(f'<li class="{f.severity.lower()}">{html.escape(name)}: {html.escape(f.text())}</li>'
                  for name, f in items)
    return f"<p>Findings:</p><ul>{lis}</ul>"


def _summary_table(results: list[WarpResult]) -> str:
    head = "".join(f"<th>{html.escape(n)}</th>" for n in ("warp", *CHECK_NAMES, "power", "overall"))
    rows = []
    for r in results:
        cells = [f'<td class="fail" colspan="{len(CHECK_NAMES)}">{html.escape(r.failure)}</td>'] if r.failure else []
        for name in CHECK_NAMES if not r.failure else ():
            c = r.checks.get(name)
            cells.append(verdict_cell(None, c.summary if c else "") if c is None or c.skipped
                         else verdict_cell(c.verdict, c.summary))
        anchor = html.escape(r.label.replace(" ", "_"))
        rows.append(f'<tr><td><a href="#{anchor}">{html.escape(r.label)}</a></td>{"".join(cells)}'
                    f'<td title="{html.escape(POWER_CAPTION)}"><small>{html.escape(power_cell(r))}</small></td>'
                    f'{verdict_cell(r.verdict, "", _warp_word(r))}</tr>')
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _section(r: WarpResult, reproduce: str, data_file: str | None) -> str:
    anchor = html.escape(r.label.replace(" ", "_"))
    if r.failure:
        return (f'<h2 id="{anchor}">{html.escape(r.label)} — FAIL</h2><p class="fail">{html.escape(r.failure)}</p>'
                f"<p>Reproduce: <code>{html.escape(reproduce)}</code></p>")
    png = warp_heatmaps_png(r.observed, r.expected, r.reference_observed, r.domain, r.label)
    img = base64.b64encode(png).decode()
    rows = "".join(
        f"<tr><td>{html.escape(name)}</td>"
        + (verdict_cell(None, c.summary) if c.skipped else verdict_cell(c.verdict, c.summary))
        + f"<td><small>{power_html(c)}</small></td>"
        + f"<td><small>{html.escape(details_text(c.to_json()))}</small></td></tr>"
        for name, c in r.checks.items())
    extra = ""
    if not r.passed:
        extra = f"<p>Reproduce: <code>{html.escape(reproduce)}</code>"
        if data_file:
            extra += f"; histograms and failing data: <code>{html.escape(data_file)}</code>"
        extra += "</p>"
    return (f'<h2 id="{anchor}">{html.escape(r.label)} — {_warp_word(r)}</h2>'
            f'<p class="meta">domain {html.escape(r.domain)}, seed {r.seed}, {r.seconds:.2f} s; judged against '
            f'{html.escape(r.judged_against)}</p>{extra}'
            f'{_findings(r)}'
            f'<img alt="histograms of {html.escape(r.label)}" src="data:image/png;base64,{img}">'
            f"<table><tr><th>check</th><th>verdict</th><th>power (90 %)</th><th>details</th></tr>{rows}</table>")


def details_text(d: dict) -> str:
    skip = {"pass", "summary", "figure", "verdict", "findings", "power"}
    parts = []
    for k, v in d.items():
        if k in skip:
            continue
        parts.append(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}")
    return ", ".join(parts)


def warp_report_html(results: list[WarpResult], level: float, meta: dict, reproduce: dict[str, str],
                     data_files: dict[str, str]) -> str:
    """The whole page; failing warps first, then those with warnings. `reproduce` and `data_files` are keyed
    by result label."""
    ordered = sorted(results, key=lambda r: _ORDER[r.verdict])
    failed = sum(not r.passed for r in results)
    warned = sum(r.verdict == "WARN" for r in results)
    meta_html = "".join(f"<li>{html.escape(str(k))}: {html.escape(str(v))}</li>" for k, v in meta.items())
    sections = "".join(_section(r, reproduce[r.label], data_files.get(r.label)) for r in ordered)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>mcval warp conformance</title><style>{CSS}{WARN_CSS}</style></head>
<body><h1>Warp conformance: {len(results) - failed} of {len(results)} warps pass{f" ({warned} with warnings)" if warned else ""}</h1>
<ul class="meta">{meta_html}<li>per-test significance level: {level:.3g} (Sidak, family-wise 0.01)</li></ul>
<p>Histograms are over each domain's parameter square, in equal-probability cells: the edges are quantiles of
the pdf's own marginals (fewer rows where float32 rounding of the samples would bias narrower ones), and the
panels draw each cell the same size, so they show the cells' coordinates, not the domain's (a correct warp's
expected panel is flat). Expected counts integrate the pdf adaptively over every cell. Residual panels show
(O−E)/√E: a correct warp is noise; structure there is a bug. Power: the smallest planted defect each check
detects in 90 % of simulated runs at this budget and level (hover for the defect). Whether each statistical
check rejects correct warps as often as its level says, and no more, is measured by
<code>mcval calibrate</code>: <a href="../calibration-latest/calibration.html">its latest page</a>.</p>
{_summary_table(results)}
{sections}
</body></html>
"""
