"""The invariance matrix as HTML: a section (one table per engine, the findings, the breaks float32 explains)
for report.html, and invariance.html, the same section as a page of its own."""
from __future__ import annotations

from html import escape

from harness.report.style import CSS


def _cell(cell: dict | None, gating: bool) -> str:
    if cell is None:
        return '<td class="na">—</td>'
    if cell.get("status") == "float32":
        return f'<td class="na">FLOAT32 {escape(", ".join(cell["beyond_float32"]))}</td>'
    if cell["pass"]:
        return f'<td class="pass">PASS {cell["ratio"]:.4f}</td>' if isinstance(cell["ratio"], float) \
            else '<td class="pass">PASS</td>'
    if cell.get("status") == "inconclusive":
        return '<td class="na">INCONCLUSIVE: no signal</td>'
    word = "FAIL" if gating else "BREAKS"
    base = cell["base_error"] or cell.get("dependence")
    if base:
        return f'<td class="{"fail" if gating else "na"}">{word}: {escape(base)}</td>'
    parts = [f'{escape(v["variant"])}: {v["ratio"]:.4f}' if isinstance(v["ratio"], float) and v["ratio"] == v["ratio"]
             else f'{escape(v["variant"])}: {escape(v["error"] or "no image")}' for v in cell["variants"]
             if v.get("status", "pass" if v["pass"] else "fail") == "fail"]
    style = "fail" if gating else "na"
    return f'<td class="{style}">{word} {"<br>".join(parts)}</td>'


def invariance_summary(payload: dict) -> str:
    """`187 of 190 checks of mcval pass, 3 beyond float32; 20 findings about the reference`."""
    gating = [c for c in payload["cells"] if c["engine"] == payload["gating_engine"]]
    passing = sum(c.get("status", "pass" if c["pass"] else "fail") == "pass" for c in gating)
    beyond = sum(c.get("status") == "float32" for c in gating)
    unjudged = sum(c.get("status") == "inconclusive" for c in gating)
    return (f'{passing} of {len(gating)} checks of {escape(payload["gating_engine"])} pass'
            + (f", {beyond} beyond float32" if beyond else "") + (f", {unjudged} not judged" if unjudged else "")
            + f'; {len(payload["findings"])} findings about the reference')


def invariance_section(payload: dict, heading: str = "h2") -> str:
    """The matrix, one table per engine, then the failures, findings and float32 limits."""
    sub = "h3" if heading == "h2" else "h2"
    cells = payload["cells"]
    gating = payload["gating_engine"]
    rows = list(dict.fromkeys(f'{c["scene"]}:{c["integrator"]}' for c in cells))
    out = [f'<{heading} id="invariances">Invariances: each engine against itself</{heading}>',
           f'<p class="meta">{invariance_summary(payload)}; per-comparison α {payload["alpha"]:.2g} (family-wise '
           f'0.01 per engine); {escape(", ".join(payload["meta"].get("engines", [])))}; seed '
           f'{payload["meta"].get("seed")}; {payload["meta"].get("seconds")} s</p>', "<ul>"]
    out += [f"<li><b>{escape(name)}</b>: {escape(inv['summary'])}</li>" for name, inv in payload["invariances"].items()]
    out.append("</ul>")
    # Where the reference engine's cells came from: references/ (stored with their provenance) or rendered now.
    sources = payload["meta"].get("reference_cells", {}).get("lines", [])
    if sources:
        out.append(f'<p class="meta">Reference cells, rendered at seed {payload["meta"].get("reference_seed")}: '
                   + "; ".join(escape(line) for line in sources) + "</p>")
    for engine in dict.fromkeys(c["engine"] for c in cells):
        by_cell = {(c["invariance"], f'{c["scene"]}:{c["integrator"]}'): c for c in cells if c["engine"] == engine}
        columns = list(dict.fromkeys(inv for inv, _ in by_cell))
        role = "under test: a FAIL fails the run" if engine == gating else "reference: a break is a finding"
        out.append(f"<{sub}>{escape(engine)} ({role})</{sub}><table><tr><th>scene:integrator</th>"
                   + "".join(f"<th>{escape(c)}</th>" for c in columns) + "</tr>")
        for key in rows:
            out.append(f"<tr><td>{escape(key)}</td>"
                       + "".join(_cell(by_cell.get((inv, key)), engine == gating) for inv in columns) + "</tr>")
        out.append("</table>")
    out.append("<p>ratio: the transformed image's mean, mapped back by the expected factor, over the base's "
               "(furthest from 1 over the variants; mean |n| for normals). FLOAT32: the listed variants broke on a "
               "scene float32 cannot represent (below, why). INCONCLUSIVE: the base render is all 0, which no "
               "rewrite can change: not judged.</p>")
    out.append(f"<p><b>How far a translation reaches.</b> {escape(payload.get('translation_reach', ''))}</p>")
    if payload.get("verdict_reason"):
        out.append(f'<p class="fail">{escape(payload["verdict_reason"])}</p>')
    for title, lines in (("Failures of the renderer under test", payload["failures"]),
                         ("Not judged", payload.get("not_judged", [])),
                         ("Findings about the reference", payload["findings"]),
                         ("Breaks float32 explains (not failures)", payload.get("float32_limits", []))):
        if lines:
            out.append(f"<{sub}>{title}</{sub}><ul>" + "".join(f"<li>{escape(x)}</li>" for x in lines) + "</ul>")
    return "\n".join(out)


def invariance_html(payload: dict) -> str:
    """The page for results.json's `invariance` block (harness.invariance.findings.invariance_payload)."""
    return ('<!DOCTYPE html><meta charset="utf-8"><title>Invariances</title>'
            f"<style>{CSS}</style>\n{invariance_section(payload, 'h1')}\n")
