"""The image part of the calibration page: false-alarm rates per kind and scale, the image scale's null
p-values, and the power curves (planted bias against the fraction of comparisons that find it)."""
from __future__ import annotations

import html

import numpy as np

from harness.report.calibration_html import _png, p_value_histograms, verdict_sentence
from harness.report.calibration_table import bias_text
from harness.report.verdict_style import VERDICT_CLASS, VERDICT_KEY
from harness.statistics.calibration_rates import CALIBRATION_LEVELS


def _rates_table(blocks: list[dict]) -> str:
    head = "".join(f"<th>comparison level {level:g}</th>" for level in CALIBRATION_LEVELS)
    rows = []
    for kind in dict.fromkeys(b["kind"] for b in blocks):
        for scale in dict.fromkeys(b["scale"] for b in blocks):
            cells = [b for b in blocks if b["kind"] == kind and b["scale"] == scale]
            tds = "".join(
                f"<td class='{VERDICT_CLASS[b['verdict']]}' title='{b['rejections']} of {b['comparisons']}; "
                f"nominal {b['level']:.4g}'>{b['false_alarm_rate']:.3f} <span class='meta'>[{b['interval'][0]:.3f}, "
                f"{b['interval'][1]:.3f}] nominal {b['level']:.3g}</span></td>" for b in cells)
            rows.append(f"<tr><td>{html.escape(kind)}</td><td>{scale}</td><td>{cells[0]['comparisons']}</td>{tds}</tr>")
    return f"<table><tr><th>kind</th><th>scale</th><th>comparisons</th>{head}</tr>{''.join(rows)}</table>"


def _power_plot(power: dict) -> str:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(9, 3), squeeze=False)
    for ax, what in zip(axes[0], ("global", "tile")):
        for integrator, entry in power.items():
            ax.semilogx(entry["biases"], entry[f"{what}_found"], marker="o", ms=3, label=integrator)
        ax.axhline(0.9, color="k", lw=0.8, ls="--")
        ax.set_title("bias of the whole image" if what == "global" else "bias of one 8×8 tile", fontsize=9)
        ax.set_xlabel("relative bias planted", fontsize=8)
        ax.set_ylabel("fraction found", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=7)
    fig.tight_layout()
    return _png(fig)


def image_calibration_sections(cal: dict) -> list[str]:
    """HTML sections for results of harness.images.calibration (its to_json())."""
    verdict = verdict_sentence(cal["pass"], cal["within"], "comparisons failed", "whole-comparison rate")
    power_rows = "".join(
        f"<tr><td>{html.escape(k)}</td><td>{v['comparisons']}</td><td>{bias_text(v['global_bias_90'])}</td>"
        f"<td>{bias_text(v['tile_bias_90'])}</td></tr>" for k, v in cal["power"].items())
    failed = "".join(f"<li>{html.escape(f)}</li>" for f in cal["failed"])
    p = np.asarray(cal["image_min_p"], float)
    return [
        "<h2>Image comparisons: false-alarm rates</h2>",
        f"<p>{cal['comparisons']} null comparisons: two independent renders of one case by engines that must "
        "agree (the tested engine twice, the reference twice, the tested engine and the closed form). Each is compared at every level; the whole "
        "comparison rejects when any scale does, a scale at its Sidak share of the level. Intervals are exact and "
        f"simultaneous at 95 % over the table ({VERDICT_KEY}). Result: {verdict}.</p>",
        _rates_table(cal["blocks"]),
        (f"<h3>Comparisons that gave no result</h3><ul>{failed}</ul>" if failed else ""),
        "<h2>Image scale: smallest p-value of the three channels</h2>",
        "<p>Not uniform even for a calibrated test (the smallest of three correlated p-values leans to 0); shown "
        "so that a pile-up near 0, a broken test, is seen.</p>",
        p_value_histograms([("image scale, min over channels", p)], columns=1),
        "<h2>Power at the validation's level</h2>",
        f"<p>Per-comparison level {cal['power_level']:.3g} (a default <code>validate</code>'s). The smallest "
        "planted relative bias found in 90 % of tested-against-tested comparisons: of the whole image (the image "
        "scale), and of one 8×8 tile (the tile scale).</p>",
        f"<table><tr><th>integrator</th><th>comparisons</th><th>whole image, 90 %</th><th>one tile, 90 %</th></tr>"
        f"{power_rows}</table>",
        _power_plot(cal["power"]),
    ]
