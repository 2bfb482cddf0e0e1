"""The calibration page: each statistical check's observed false-alarm rate beside its nominal level."""
from __future__ import annotations

import base64
import html
import io

import numpy as np

from harness.statistics.calibration_rates import Rate
from harness.report.style import CSS


def _png(fig) -> str:
    import matplotlib.pyplot as plt
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)  # laid out by tight_layout already: no second draw for a tight box
    plt.close(fig)
    return f'<img alt="p-value histograms" src="data:image/png;base64,{base64.b64encode(buf.getvalue()).decode()}">'


def p_value_histograms(panels: list[tuple[str, np.ndarray]], columns: int = 4) -> str:
    """One histogram of null p-values per panel (uniform on [0, 1] for a calibrated test)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = max(1, -(-len(panels) // columns))
    fig, axes = plt.subplots(rows, columns, figsize=(3.2 * columns, 2.2 * rows), squeeze=False)
    for ax, (title, p) in zip(axes.ravel(), panels):
        ax.hist(p, bins=20, range=(0, 1), color="#4a7ab0")
        ax.axhline(len(p) / 20, color="k", lw=0.8, ls="--")
        ax.set_title(title, fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in axes.ravel()[len(panels):]:
        ax.axis("off")
    fig.tight_layout()
    return _png(fig)


def rate_cells(rates: list[Rate]) -> str:
    """Table cells: observed rate and interval per level, coloured by its verdict (Rate.verdict)."""
    from harness.report.verdict_style import VERDICT_CLASS
    return "".join(
        f"<td class='{VERDICT_CLASS[r.verdict]}' title='{r.rejections} of {r.count}; interval "
        f"[{r.low:.3f}, {r.high:.3f}]'>{r.observed:.3f} <span class='meta'>[{r.low:.3f}, {r.high:.3f}]</span></td>"
        for r in rates)


def rates_table(entries, subject: str, runs: str) -> str:
    """One row per calibrated check (harness.warps.calibration.CheckCalibration: its warp or BSDF row, the check,
    how many null runs, the rate at each level, the KS p of its p-values); `subject` and `runs` head the first and
    third columns."""
    from harness.statistics.calibration_rates import CALIBRATION_LEVELS
    head = "".join(f"<th>rate at {level:g}</th>" for level in CALIBRATION_LEVELS)
    rows = "".join(
        f"<tr><td>{html.escape(e.warp)}</td><td>{e.check}</td><td>{len(e.p_values)}</td>{rate_cells(e.rates)}"
        f"<td>{e.uniformity:.3g}</td></tr>" for e in entries)
    return (f"<table><tr><th>{subject}</th><th>check</th><th>{runs}</th>{head}<th>KS p (uniform p-values)</th></tr>"
            f"{rows}</table>")


def verdict_sentence(sound: bool, within: bool, missing: str, judged: str = "rate") -> str:
    """The calibration's result in a sentence: `within` says of every `judged` rate; `missing` names what
    can fail to give a result."""
    if not sound:
        return f"<b>a rate lies above its interval (liberal: more false alarms than stated), or {missing}</b>"
    if within:
        return f"every {judged} is within its interval of the nominal level"
    return "no rate is above its nominal level; some are below their interval (conservative, in yellow)"


def calibration_page(title: str, intro: str, sections: list[str], meta: dict) -> str:
    meta_html = "".join(f"<li>{html.escape(str(k))}: {html.escape(str(v))}</li>" for k, v in meta.items())
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{CSS}</style></head><body><h1>{html.escape(title)}</h1><p>{intro}</p>"
            f"<ul class='meta'>{meta_html}</ul>{''.join(sections)}</body></html>")


def warp_calibration_html(cal, meta: dict, more: list[str] = ()) -> str:
    """The calibration page with its warp part (the table, pooled rows first, and the p-value histograms),
    then the sections `more` (the image part)."""
    from harness.report.verdict_style import VERDICT_KEY
    table = rates_table(cal.pooled + cal.entries, "warp", "null tests")
    panels = [(f"{e.warp}: {e.check}", e.p_values) for e in cal.pooled + cal.entries]
    verdict = verdict_sentence(cal.sound, cal.within, "warps gave no p-values")
    intro = (f"Every correct warp of the matrix at {cal.seeds} seeds ({cal.samples:,} samples each, the matrix's "
             "budget and cells): each rejection is a false alarm. A cell shows the observed rate and its exact "
             f"(Clopper-Pearson) interval, simultaneous at 95 % over all the intervals of the page ({VERDICT_KEY}). "
             f"Result: {verdict}.")
    failed = "".join(f"<li>{html.escape(f)}</li>" for f in cal.failed)
    failed = f"<h3>Warps that gave no p-values</h3><ul>{failed}</ul>" if failed else ""
    return calibration_page("Calibration of the warp checks", intro,
                            ["<h2>False-alarm rates</h2>", table, failed, "<h2>Null p-values</h2>",
                             p_value_histograms(panels), *more], meta)
