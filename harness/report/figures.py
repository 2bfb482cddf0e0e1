"""A matplotlib figure as PNG bytes, for the plots (curves, scatter) the reports draw with matplotlib; the rows of
picture panels are painted without it (panels.py)."""
from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402


def figure_png(fig: Figure, dpi: int) -> bytes:
    """`fig` as PNG, then closed (pyplot keeps every open figure)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return buf.getvalue()
