"""The main report page: warps summary, regression since the last run, and every image comparison."""
from __future__ import annotations

import base64
import html

import numpy as np

from harness.comparison.compare import Comparison
from harness.comparison.finite import SIDES
from harness.images.references import CLOSED_FORM
from harness.images.result import ImageResult
from harness.report.idiff_text import LEGEND, idiff_sentence
from harness.report.image_plots import comparison_png
from harness.report.invariance_html import invariance_section, invariance_summary
from harness.report.reproduce import reproduce_line
from harness.report.style import CSS
from harness.integrators import entry


def _esc(x) -> str:
    return html.escape(str(x))


def _verdict(ok: bool | str) -> str:
    """PASS or FAIL for a bool; a verdict word ("INCONCLUSIVE" in the warning colour) as it is."""
    word = ("PASS" if ok else "FAIL") if isinstance(ok, bool) else ok
    kind = {"PASS": "pass", "FAIL": "fail"}.get(word, "warn")
    return f'<span class="{kind}">{word}</span>'


def _seconds(timings: dict, key: str) -> str:
    """A phase's seconds, or a dash where an engine has no such phase."""
    return f"{timings[key]:.3f}" if key in timings else "—"


def reproduce_command(result: ImageResult, run: dict | None = None) -> str:
    """The command that renders and judges this case again (`run`: the run's invocation, see reproduce)."""
    return reproduce_line("images", ["--only", result.case.key], result.run_seed, run, result.case.source)


def _bad_pixels(comparison: Comparison) -> str:
    """E.g. "non-finite pixels: 12 in the test image at (3, 7), (3, 8), …": every kind and side, the
    locations (row, column) the check kept; empty when the check passed."""
    lines = []
    for side in SIDES:
        d = getattr(comparison.finite, side)
        for kind, n, at in (("non-finite", d.nonfinite, d.nonfinite_at), ("negative", d.negative, d.negative_at)):
            if n:
                more = f", … ({n - len(at)} more)" if n > len(at) else ""
                lines.append(f"{kind} pixels: {n} in the {side} image at {', '.join(map(str, at))}{more}")
    return "".join(f"<p class='fail'>{_esc(line)}</p>" for line in lines)


def _picture(r: ImageResult, name: str, comparison: Comparison) -> str:
    """The row of panels; NaN and Inf shown as 0 (the bad pixels are red on the p-value map, which
    counts them as certain rejections, and listed above it)."""
    signed = entry(r.case.integrator).signed
    tested = np.nan_to_num(r.tested.mean, nan=0.0, posinf=0.0, neginf=0.0)
    ref = np.nan_to_num(r.references[name].summary.mean_image, nan=0.0, posinf=0.0, neginf=0.0)
    if not signed and not ref.max() > 0:
        # FLIP's HDR mode cannot place its exposures on an all-black reference and ends the process.
        return "<p class='meta'>No pictures: the reference holds no positive value.</p>"
    shown = "closed form" if r.references[name].source == CLOSED_FORM else name.capitalize()
    png = comparison_png(tested, ref, comparison, signed, shown, r.engine)
    return (f'<img alt="{_esc(r.case.key)} against {_esc(name)}" src="data:image/png;base64,'
            f'{base64.b64encode(png).decode()}">')


def entry_html(r: ImageResult, run: dict | None = None) -> str:
    """One case's section of the report."""
    parts = [f'<h3 id="{_esc(r.case.key)}">{_esc(r.case.scene)} — {_esc(r.case.integrator)}: {_verdict(r.verdict)}</h3>']
    if r.inconclusive:
        parts.append(f'<p class="warn">{_esc(r.inconclusive)}</p>')
    if r.note:
        parts.append(f'<p class="fail">{_esc(r.note)}</p>')
    if r.reference_problem:
        parts.append(f'<p class="fail">{_esc(r.reference_problem)}</p>')
    if r.reference_fit is not None:
        parts.append(f"<p class='meta'>{_esc(r.reference_fit.summary)}</p>")
    if not r.passed:
        parts.append(f"<p>Reproduce: <code>{_esc(reproduce_command(r, run))}</code></p>")
    if r.case.source:
        parts.append(f"<p class='meta'>scene file: {_esc(r.case.source)}</p>")
        parts.extend(f"<p class='meta'>note: {_esc(note)}</p>" for note in r.case.notes)
    parts.append(f"<p>{_esc(idiff_sentence(r.idiff))}</p>")
    if r.error is not None or r.tested is None:
        parts.append(f'<p class="fail">Render failed: {_esc(r.error)}; nothing to compare.</p>')
        if r.error_output:
            parts.append(f"<p>What it printed last:</p><pre>{_esc(r.error_output)}</pre>")
        return "".join(parts)
    tested = r.engine
    for name, comparison in r.comparisons.items():
        ref = r.references[name]
        finite = comparison.finite
        rows = (f"<tr><td>finite</td><td colspan='5'>{_esc(finite.summary)}</td>"
                f"<td>{_verdict(finite.passed)}</td></tr>")
        if comparison.independence is not None:
            rows += (f"<tr><td>independent</td><td colspan='5'>{_esc(comparison.independence.summary)}</td>"
                     f"<td>{_verdict(comparison.independence.passed)}</td></tr>")
        if comparison.variance is not None:
            rows += (f"<tr><td>variance</td><td colspan='5'>{_esc(comparison.variance.summary)}</td>"
                     f"<td>{_verdict(comparison.variance.passed)}</td></tr>")
        rows += "".join(f"<tr><td>{s.scale}</td><td>{s.tests}</td><td>{s.level:.2g}</td><td>{s.min_p:.2g}</td>"
                        f"<td>{s.failures}</td><td>{s.worst}</td><td>{_verdict(s.passed)}</td></tr>"
                        for s in comparison.scales)
        metrics = "".join(f"<tr><td>{_esc(k)}</td><td>{v:.4g}</td></tr>" for k, v in comparison.metrics.items())
        parts.append(
            f"<p class='meta'>against {_esc(name)} ({ref.spp} spp × "
            f"{'one image' if r.reference_fit is not None else f'{ref.summary.image.k} batches'}"
            f"{', ' + _esc(r.reference_source) if ref.source != CLOSED_FORM else ''}); {_esc(tested)} {r.tested.spp} spp × "
            f"{r.tested.count} batches, seed {r.seed}; smallest detectable bias of the image mean "
            f"{comparison.detectable_bias:.2%}</p>"
            + _bad_pixels(comparison) + _picture(r, name, comparison) +
            f"<div style='display:flex;gap:2em;align-items:flex-start'><table><tr><th>scale</th><th>tests</th><th>level</th><th>min p</th>"
            f"<th>fails</th><th>worst (row, col)</th><th></th></tr>{rows}</table>"
            f"<table><tr><th>metric</th><th>value</th></tr>{metrics}</table>"
            f"<table><tr><th>seconds</th><th>{_esc(tested)}</th><th>{_esc(name)}</th></tr>"
            + "".join(f"<tr><td>{_esc(k)}</td><td>{_seconds(r.tested.seconds, k)}</td>"
                      f"<td>{_seconds(ref.seconds, k)}</td></tr>"
                      for k in ("load", "build", "first", "render", "total"))
            + "</table></div>")
    parts.append(_strategies_html(r))
    return "".join(parts)


def _strategies_html(r: ImageResult) -> str:
    """The strategy check: its verdict and reason, and each pair's scales (or why it did not run)."""
    check = r.strategies
    if check is None:
        skipped = r.decision.strategies_skipped
        return f"<p class='meta'>strategies not compared: {_esc(skipped)}</p>" if skipped else ""
    verdict = "FAIL" if check.disagree else "PASS" if check.verdict == "AGREE" else "INCONCLUSIVE"
    rows = "".join(f"<tr><td>{_esc(p.first)} vs {_esc(p.second)}</td>"
                   + "".join(f"<td>{s.min_p:.2g} (level {s.level:.2g})</td>" for s in p.comparison.scales)
                   + f"<td>{_verdict(p.comparison.verdict)}</td></tr>" for p in check.pairs)
    scales = "".join(f"<th>{_esc(s.scale)}: min p</th>" for s in check.pairs[0].comparison.scales)
    return (f"<p>strategies of {_esc(r.engine)} ({check.verdict}{', ' + _esc(check.odd) + ' differs' if check.odd else ''}): "
            f"{_verdict(verdict)} {_esc(check.reason)}</p>"
            f"<table><tr><th>pair</th>{scales}<th></th></tr>{rows}</table>")


def _regression_html(regression: list[dict] | None, baseline: str | None) -> str:
    if regression is None:
        return "<p class='meta'>No earlier run to compare with.</p>"
    flagged = [r for r in regression if r["flags"]]
    if not flagged:
        return f"<p>Since {_esc(baseline)}: no change beyond noise in verdict, image mean or time.</p>"
    rows = "".join(f"<tr><td>{_esc(r['scene'])}</td><td>{_esc(r['integrator'])}</td>"
                   f"<td class='fail'>{_esc('; '.join(r['flags']))}</td></tr>" for r in flagged)
    return (f"<p>Since {_esc(baseline)}, changes beyond noise:</p>"
            f"<table><tr><th>scene</th><th>integrator</th><th>change</th></tr>{rows}</table>")


def _inconclusive_count(results: list[ImageResult]) -> str:
    n = sum(r.verdict == "INCONCLUSIVE" for r in results)
    return f", {n} inconclusive" if n else ""


def report_html(results: list[ImageResult], alpha: float, warps: dict | None, meta: dict,
                regression: list[dict] | None, baseline: str | None, bench_href: str | None = None,
                invariance: dict | None = None, calibration_href: str | None = None, run: dict | None = None) -> str:
    """The whole page. Within each integrator's section, failures come first. `bench_href` links the
    latest speed-against-error page, if there is one; `invariance` is the run's invariance block, whose
    matrix ends the page (its own page, invariance.html, is linked); `calibration_href` links the latest
    `calibrate` page, if there is one; `run`: the run's invocation, repeated by each reproduce line."""
    failed = sum(not r.passed for r in results)
    summary = [f"<li>Images: {len(results) - failed} of {len(results)} comparisons pass"
               f"{_inconclusive_count(results)} "
               f"(per-comparison α {alpha:.2g}, family-wise 0.01 over the run)</li>"]
    if warps is not None:
        n_pass = sum(w["pass"] for w in warps["warps"])
        summary.append(f'<li><a href="warps.html">Warp conformance</a>: {n_pass} of {len(warps["warps"])} warps '
                       f'pass {_verdict(warps["pass"])}</li>')
    if invariance:
        summary.append(f'<li><a href="#invariances">Invariances</a> (<a href="invariance.html">own page</a>): '
                       f'{invariance_summary(invariance)} {_verdict(invariance["pass"])}</li>')
    if bench_href:
        summary.append(f'<li><a href="{_esc(bench_href)}">Speed against error</a> (the latest `make bench`)</li>')
    if calibration_href:
        summary.append(f'<li><a href="{_esc(calibration_href)}">Calibration</a>: the measured false-alarm rates '
                       'and power of these tests (the latest `mcval calibrate`)</li>')
    summary += [f"<li>{_esc(k)}: {_esc(v)}</li>" for k, v in meta.items()]
    sections = []
    for integrator in dict.fromkeys(r.case.integrator for r in results):
        cases = sorted((r for r in results if r.case.integrator == integrator), key=lambda r: r.passed)
        if not cases:
            continue
        n_ok = sum(r.passed for r in cases)
        links = " ".join(f'<a href="#{_esc(r.case.key)}">{_esc(r.case.scene)}</a> {_verdict(r.verdict)}' for r in cases)
        sections.append(f"<h2>{_esc(integrator)}: {n_ok} of {len(cases)} scenes pass</h2><p>{links}</p>"
                        + "".join(entry_html(r, run) for r in cases))
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>mcval report</title><style>{CSS}</style></head>
<body><h1>mcval validation report: {_verdict(failed == 0 and (warps is None or warps["pass"])
                                             and (invariance is None or invariance["pass"]))}</h1>
<ul class="meta">{''.join(summary)}</ul>
<h2>Regression</h2>{_regression_html(regression, baseline)}
<p>Each engine renders independent batches; Welch's t-test compares them per pixel, per 8×8 tile and for
the whole image. The p-value map shows log10(p / level) at the pixel and tile scales: red pixels are where a
difference is beyond noise. {_esc(LEGEND)}.</p>
{''.join(sections)}
{invariance_section(invariance, "h2") if invariance else ""}
</body></html>
"""
