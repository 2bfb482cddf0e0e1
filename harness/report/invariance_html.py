"""invariance.html: the invariance matrix of one run, one table per engine, and the findings."""
from __future__ import annotations

from html import escape

from harness.report.style import CSS


def _cell(cell: dict | None, gating: bool) -> str:
    if cell is None:
        return '<td class="na">—</td>'
    if cell["pass"]:
        return f'<td class="pass">PASS {cell["ratio"]:.4f}</td>' if isinstance(cell["ratio"], float) \
            else '<td class="pass">PASS</td>'
    word = "FAIL" if gating else "BREAKS"
    if cell["base_error"]:
        return f'<td class="fail">{word}: {escape(cell["base_error"])}</td>'
    parts = [f'{escape(v["variant"])}: {v["ratio"]:.4f}' if isinstance(v["ratio"], float) and v["ratio"] == v["ratio"]
             else f'{escape(v["variant"])}: {escape(v["error"] or "no image")}' for v in cell["variants"] if not v["pass"]]
    style = "fail" if gating else "na"
    return f'<td class="{style}">{word} {"<br>".join(parts)}</td>'


def invariance_html(payload: dict) -> str:
    """The page for results.json's `invariance` block (harness.invariance.findings.invariance_payload)."""
    cells = payload["cells"]
    gating = payload["gating_engine"]
    rows = list(dict.fromkeys(f'{c["scene"]}:{c["integrator"]}' for c in cells))
    out = ['<!DOCTYPE html><meta charset="utf-8"><title>Invariances</title>', f"<style>{CSS}</style>",
           "<h1>Invariances: each engine against itself</h1>",
           f'<p class="meta">per-comparison α {payload["alpha"]:.2g} (family-wise 0.01 per engine); '
           f'{escape(", ".join(payload["meta"].get("engines", [])))}; seed {payload["meta"].get("seed")}; '
           f'{payload["meta"].get("seconds")} s</p>', "<ul>"]
    out += [f"<li><b>{escape(name)}</b>: {escape(inv['summary'])}</li>" for name, inv in payload["invariances"].items()]
    out.append("</ul>")
    for engine in dict.fromkeys(c["engine"] for c in cells):
        mine = {(c["invariance"], f'{c["scene"]}:{c["integrator"]}'): c for c in cells if c["engine"] == engine}
        columns = list(dict.fromkeys(inv for inv, _ in mine))
        role = "under test: a FAIL fails the run" if engine == gating else "reference: a break is a finding"
        out.append(f"<h2>{escape(engine)} ({role})</h2><table><tr><th>scene:integrator</th>"
                   + "".join(f"<th>{escape(c)}</th>" for c in columns) + "</tr>")
        for key in rows:
            out.append(f"<tr><td>{escape(key)}</td>"
                       + "".join(_cell(mine.get((inv, key)), engine == gating) for inv in columns) + "</tr>")
        out.append("</table>")
    out.append("<p>ratio: the transformed image's mean, mapped back by the expected factor, over the base's "
               "(furthest from 1 over the variants; mean |n| for normals).</p>")
    for title, lines in (("Failures of the renderer under test", payload["failures"]),
                         ("Findings about the reference", payload["findings"])):
        if lines:
            out.append(f"<h2>{title}</h2><ul>" + "".join(f"<li>{escape(x)}</li>" for x in lines) + "</ul>")
    return "\n".join(out) + "\n"
