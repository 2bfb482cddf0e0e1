"""The row of pictures for one comparison: ours, Mitsuba, signed difference, p-value map, FLIP map."""
from __future__ import annotations

import numpy as np

from harness.comparison.compare import Comparison
from harness.comparison.metrics import flip_map
from harness.report.figures import figure_png, panel_row


def display(img: np.ndarray, signed: bool) -> np.ndarray:
    """What a person should see: normals as (n + 1) / 2, radiance clipped and sRGB-encoded."""
    if signed:
        return np.clip((img + 1) / 2, 0, 1)
    x = np.clip(img, 0, 1)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def rejection_map(comparison: Comparison) -> np.ndarray:
    """log10(p / level) at the pixel and tile scales, whichever is lower: below 0 is rejected."""
    maps = [np.log10(np.maximum(s.p_map, 1e-300) / s.level) for s in comparison.scales if s.scale != "image"]
    return np.minimum(*maps)


def comparison_png(ours: np.ndarray, reference: np.ndarray, comparison: Comparison, signed: bool,
                   reference_name: str = "Mitsuba", tested_name: str = "ours") -> bytes:
    """PNG of five panels, each with its own scale bar where it has one; the tested image is titled
    `tested_name`."""
    diff = (ours - reference).mean(axis=-1)
    limit = float(np.percentile(np.abs(diff), 99.5)) or 1e-6
    flip = comparison.flip_map
    if flip is None or flip.shape != ours.shape[:2]:  # a comparison made without its metrics
        flip, _ = flip_map(ours, reference, signed)
    h, w = ours.shape[:2]
    fig, axes, bars = panel_row([False, False, True, True, True], panel=2.3 * min(w / h, 1.6), height=2.9,
                                left=0.1, gap=0.15, bottom=0.1, top=0.35, bar_room=0.55)
    axes[0].imshow(display(ours, signed), interpolation="nearest")
    axes[0].set_title(tested_name, fontsize=9)
    axes[1].imshow(display(reference, signed), interpolation="nearest")
    axes[1].set_title(reference_name, fontsize=9)
    im = axes[2].imshow(diff, cmap="RdBu_r", vmin=-limit, vmax=limit, interpolation="nearest")
    axes[2].set_title(f"{tested_name} − reference (mean of RGB)", fontsize=9)
    fig.colorbar(im, cax=bars[0])
    im = axes[3].imshow(rejection_map(comparison), cmap="RdYlGn", vmin=-3, vmax=3, interpolation="nearest")
    axes[3].set_title("log10(p / level): red rejects", fontsize=9)
    fig.colorbar(im, cax=bars[1])
    im = axes[4].imshow(flip, cmap="magma", vmin=0, vmax=1, interpolation="nearest")
    axes[4].set_title("FLIP", fontsize=9)
    fig.colorbar(im, cax=bars[2])
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    for bar in bars:
        bar.tick_params(labelsize=7)
    return figure_png(fig, dpi=72)
