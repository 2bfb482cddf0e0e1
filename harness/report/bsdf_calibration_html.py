"""The BSDF part of the calibration page: the statistical checks' false-alarm rates, the deterministic checks'
failures on correct BSDFs, the planted defects' power, and the null p-values."""
from __future__ import annotations

import html

from harness.report.calibration_html import p_value_histograms, rates_table, verdict_sentence
from harness.report.verdict_style import VERDICT_KEY


def _deterministic_table(cal) -> str:
    rows = "".join(
        f"<tr><td>{html.escape(d.row)}</td><td>{d.check}</td><td>{d.runs}</td>"
        f"<td class='{'fail' if d.failures else 'pass'}'>{d.failures} <span class='meta'>[{d.low:.3f}, "
        f"{d.high:.3f}]</span></td><td>{html.escape(d.example or '')}</td></tr>" for d in cal.deterministic)
    return ("<table><tr><th>BSDF</th><th>check</th><th>null runs</th><th>failures [interval of the rate]</th>"
            f"<th>first failure</th></tr>{rows}</table>")


def _power_table(cal) -> str:
    rows = "".join(
        f"<tr><td>{p.check}</td><td>{html.escape(p.defect)}</td><td>{'' if p.level is None else f'{p.level:g}'}</td>"
        f"<td>{p.stated:.0%}</td><td class='{'pass' if p.holds else 'fail'}'>{p.found} of {p.runs} "
        f"<span class='meta'>[{p.low:.3f}, {p.high:.3f}]</span></td></tr>" for p in cal.power)
    return ("<table><tr><th>check</th><th>planted defect</th><th>per-test level</th><th>stated power</th>"
            f"<th>found [interval]</th></tr>{rows}</table>")


def bsdf_calibration_sections(cal) -> list[str]:
    """HTML sections for a harness.bsdfs.calibration.BsdfCalibration."""
    verdict = verdict_sentence(cal.sound, cal.within, "a deterministic check failed a correct BSDF, a planted "
                               "defect was found less often than stated, or a row gave no result")
    failed = "".join(f"<li>{html.escape(f)}</li>" for f in cal.failed)
    panels = [(f"{e.warp}: {e.check}", e.p_values) for e in cal.pooled + cal.entries]
    return [
        "<h2>BSDF checks: false-alarm rates</h2>",
        f"<p>Correct BSDFs at {cal.seeds} seeds each ({cal.samples:,} samples a run, every check as the matrix "
        "runs it): each rejection is a false alarm. The row <i>uniform_lambert</i> has weights of mean exactly 1, "
        "the energy check's edge, where its rate is the nominal one (a BSDF that loses energy can only be "
        f"conservative there). Intervals are exact and simultaneous at 95 % over the section ({VERDICT_KEY}). "
        f"Result: {verdict}.</p>",
        rates_table(cal.pooled + cal.entries, "BSDF", "null runs"),
        f"<p class='meta'>p = 1 at every seed, nothing random tested (left out of the rates): "
        f"{html.escape('; '.join(cal.degenerate))}</p>" if cal.degenerate else "",
        "<h3>Deterministic checks on correct BSDFs (a failure is a false FAIL)</h3>", _deterministic_table(cal),
        "<h3>Power: defects of the stated size, planted</h3>",
        "<p>The energy check states the excess it finds 90 % of the time at its level; that excess is planted "
        "(the albedo raised by it) and counted. The weight check allows a relative error of 10<sup>-3</sup>; "
        "weights off by twice that are planted.</p>", _power_table(cal),
        f"<h3>Rows that gave no result</h3><ul>{failed}</ul>" if failed else "",
        "<h3>Null p-values</h3>", p_value_histograms(panels)]
