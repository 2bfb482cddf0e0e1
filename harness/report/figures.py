"""The reports' figures: a row of picture panels placed by hand, and a figure as PNG bytes.

Matplotlib's layout engines measure every tick label to place the axes; for a fixed row of panels the
arithmetic of `panel_row` gives the same picture in a fraction of the time (the layout was most of a
report's cost).
"""
from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402


def panel_row(bars: list[bool], *, panel: float, height: float, left: float = 0.1, gap: float = 0.15,
              bottom: float = 0.1, top: float = 0.3, bar_room: float = 0.75) -> tuple[Figure, list[Axes], list[Axes]]:
    """A figure with one panel per entry of `bars` (sizes in inches) and a colour-bar axis after each panel
    whose entry is True. `left` and `gap` leave room for y labels, `bottom` for x labels, `top` for titles."""
    width = left + sum(panel + (bar_room if b else 0.0) + gap for b in bars)
    inner = height - bottom - top
    fig = plt.figure(figsize=(width, height))
    axes, caxes, x = [], [], left
    for has_bar in bars:
        axes.append(fig.add_axes((x / width, bottom / height, panel / width, inner / height)))
        x += panel
        if has_bar:
            caxes.append(fig.add_axes(((x + 0.1) / width, (bottom + 0.1 * inner) / height, 0.12 / width,
                                       0.8 * inner / height)))
            x += bar_room
        x += gap
    return fig, axes, caxes


def figure_png(fig: Figure, dpi: int) -> bytes:
    """`fig` as PNG, then closed (pyplot keeps every open figure)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return buf.getvalue()
