"""Histogram heat maps of a warp: observed, expected, the reference's samples and the residuals."""
from __future__ import annotations

import numpy as np

from harness.report.figures import figure_png, panel_row
from harness.warps.domains import get_domain

#: Axis labels of each domain's parameter square.
_AXES = {"square": ("x", "y"), "tent": ("(x+1)/2", "(y+1)/2"), "disk": ("r²", "φ/2π"),
         "sphere": ("(cos θ+1)/2", "φ/2π"), "hemisphere": ("cos θ", "φ/2π")}


def warp_heatmaps_png(observed: np.ndarray, expected: np.ndarray, reference: np.ndarray | None,
                      domain: str, title: str) -> bytes:
    """A row of heat maps over the parameter square's cells (equal-probability ones, drawn equally large), as PNG.

    Panels: our samples, the pdf's expected counts, Mitsuba's samples (if any),
    and the Pearson residual (O - E) / sqrt(E), which shows where a fit fails.
    """
    get_domain(domain)  # fail early on an unknown domain
    panels = [("observed (ours)", observed), ("expected (pdf)", expected)]
    if reference is not None:
        panels.append(("observed (Mitsuba)", reference))
    vmax = max(float(np.max(p)) for _, p in panels) or 1.0
    # The counts share one colour bar (after the last count panel); the residuals have their own.
    bars = [False] * (len(panels) - 1) + [True, True]
    fig, axes, (count_bar, resid_bar) = panel_row(bars, panel=2.45, height=3.2, left=0.55, gap=0.55,
                                                  bottom=0.5, top=0.55, bar_room=0.95)
    xlabel, ylabel = (f"{axis}, equal-prob. cells" for axis in _AXES[domain])
    for ax, (name, data) in zip(axes, panels):
        im = ax.imshow(data.T, origin="lower", extent=(0, 1, 0, 1), cmap="viridis", vmin=0, vmax=vmax,
                       aspect="auto", interpolation="nearest")
        ax.set_title(name, fontsize=9)
    fig.colorbar(im, cax=count_bar, label="samples per cell")
    with np.errstate(divide="ignore", invalid="ignore"):
        resid = np.where(expected > 0, (observed - expected) / np.sqrt(expected), np.where(observed > 0, 10.0, 0.0))
    rim = axes[-1].imshow(resid.T, origin="lower", extent=(0, 1, 0, 1), cmap="RdBu_r", vmin=-5, vmax=5,
                          aspect="auto", interpolation="nearest")
    axes[-1].set_title("(O−E)/√E", fontsize=9)
    fig.colorbar(rim, cax=resid_bar)
    for ax in axes:
        ax.set_xlabel(xlabel, fontsize=8)
        ax.set_ylabel(ylabel, fontsize=8)
        ax.tick_params(labelsize=7)
    for bar in (count_bar, resid_bar):
        bar.tick_params(labelsize=7)
    fig.suptitle(title, fontsize=10)
    return figure_png(fig, dpi=80)
