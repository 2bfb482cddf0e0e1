"""Histogram heat maps of a warp: observed, expected, the reference's samples and the residuals."""
from __future__ import annotations

import numpy as np

from harness.report.panels import Bar, Panel, row_png
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
    counts = [("observed (tested)", observed), ("expected (pdf)", expected)]
    if reference is not None:
        counts.append(("observed (Mitsuba)", reference))
    # A pdf that is not finite somewhere expects inf or NaN counts: drawn at the top of the colour bar (NaN at 0).
    vmax = max(float(np.max(c, where=np.isfinite(c), initial=0.0)) for _, c in counts) or 1.0
    counts = [(name, np.nan_to_num(c, nan=0.0, posinf=vmax, neginf=0.0)) for name, c in counts]
    with np.errstate(divide="ignore", invalid="ignore"):
        resid = np.where(expected > 0, (observed - expected) / np.sqrt(expected), np.where(observed > 0, 10.0, 0.0))
    resid = np.nan_to_num(resid, nan=0.0, posinf=10.0, neginf=-10.0)
    axes = tuple(f"{axis}, equal-prob. cells" for axis in _AXES[domain])
    # The counts share one colour bar (after the last count panel); the residuals have their own.
    count_bar, resid_bar = Bar("viridis", 0.0, vmax, "samples per cell"), Bar("RdBu_r", -5.0, 5.0)
    bars = [None] * (len(counts) - 1) + [count_bar, resid_bar]
    named = counts + [("(O−E)/√E", resid)]
    # Cell (i, j) is x bin i, y bin j: shown with y upwards.
    panels = [Panel(bar_of.colour(np.flipud(data.T)), name, bar, axes)
              for (name, data), bar, bar_of in zip(named, bars, [count_bar] * len(counts) + [resid_bar])]
    return row_png(panels, size=170, title=title)
