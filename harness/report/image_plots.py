"""The row of pictures for one comparison: the tested image, the reference, signed difference, p-value map,
FLIP map."""
from __future__ import annotations

import numpy as np

from harness.comparison.compare import Comparison
from harness.comparison.metrics import flip_map
from harness.report.panels import Bar, Panel, row_png


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


def comparison_png(tested: np.ndarray, reference: np.ndarray, comparison: Comparison, signed: bool,
                   reference_name: str = "reference", tested_name: str = "tested") -> bytes:
    """PNG of five panels, the last three each with its own scale bar; the tested image is titled
    `tested_name`."""
    diff = (tested - reference).mean(axis=-1)
    limit = float(np.percentile(np.abs(diff), 99.5)) or 1e-6
    flip = comparison.flip_map
    if flip is None or flip.shape != tested.shape[:2]:  # a comparison made without its metrics
        flip, _ = flip_map(tested, reference, signed)
    bars = (Bar("RdBu_r", -limit, limit), Bar("RdYlGn", -3.0, 3.0), Bar("magma", 0.0, 1.0))
    maps = (diff, rejection_map(comparison), flip)
    titles = (f"{tested_name} − reference (mean of RGB)", "log10(p / level): red rejects", "FLIP")
    panels = [Panel(display(tested, signed), tested_name), Panel(display(reference, signed), reference_name)]
    panels += [Panel(bar.colour(data), title, bar) for bar, data, title in zip(bars, maps, titles)]
    return row_png(panels)
