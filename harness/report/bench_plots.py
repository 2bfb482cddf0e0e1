"""Plots of speed against error: relMSE against samples and against seconds, and equal-time images."""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness.bench.run import CaseBench  # noqa: E402
from harness.report.figures import figure_png  # noqa: E402
from harness.report.image_plots import display  # noqa: E402
from harness.integrators import entry

#: Colour per engine, in the order the engines first appear in a bench's curves.
COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")
#: Line style per sampler: independent solid, stratified ones dashed or dotted.
STYLES = {"independent": "o-", "sobol": "s--", "ldsampler": "s--", "multijitter": "^:"}


def _look(label: str, labels) -> tuple[str | None, str]:
    """Colour by engine (its place among the engines of `labels`), line style by sampler, for a curve label
    "engine/sampler"."""
    engine, _, sampler = label.partition("/")
    engines = list(dict.fromkeys(k.partition("/")[0] for k in labels))
    return COLORS[engines.index(engine) % len(COLORS)], STYLES.get(sampler, "o-")


def convergence_png(bench: CaseBench) -> bytes:
    """Two log-log panels with the spread (min to max) of the runs at each step."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)
    for name, curve in bench.curves.items():
        spp = np.array([s.spp for s in curve.steps], float)
        sec = np.array([np.median(s.seconds) for s in curve.steps])
        err = np.array([s.relmse for s in curve.steps])
        med = np.median(err, axis=1)
        color, style = _look(name, bench.curves)
        slope = curve.fit("spp")[0]
        for ax, x in ((axes[0], spp), (axes[1], sec)):
            ax.fill_between(x, np.clip(err.min(axis=1), 1e-12, None), np.clip(err.max(axis=1), 1e-12, None),
                            color=color, alpha=0.2)
            ax.plot(x, np.clip(med, 1e-12, None), style, color=color, label=f"{name} (slope {slope:.2f})")
    axes[0].set_xlabel("samples per pixel")
    axes[1].set_xlabel("render seconds (median of runs)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel("relMSE (reference noise removed)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{bench.case.scene} — {bench.case.integrator}", fontsize=10)
    return figure_png(fig, dpi=72)


def equal_time_png(bench: CaseBench) -> bytes:
    """Each engine's image at the ladder step closest to our renderer's time at 64 spp (or its nearest step)."""
    tested = bench.curves.get(f"{bench.tested}/independent") or bench.curves.get(bench.tested)
    budget = None
    if tested:
        step = min(tested.steps, key=lambda s: abs(np.log2(s.spp / 64)))
        budget = float(np.median(step.seconds))
    names = list(bench.curves)
    fig, axes = plt.subplots(1, len(names) + 1, figsize=(3 * (len(names) + 1), 3.2), constrained_layout=True)
    signed = entry(bench.case.integrator).signed
    for ax, name in zip(axes, names):
        curve = bench.curves[name]
        times = np.array([np.median(s.seconds) for s in curve.steps])
        k = int(np.argmin(np.abs(np.log(times / budget)))) if budget else len(times) - 1
        step = curve.steps[k]
        ax.imshow(display(curve.images[step.spp], signed), interpolation="nearest")
        ax.set_title(f"{name}: {step.spp} spp, {times[k]:.3f} s", fontsize=8)
    axes[-1].imshow(display(bench.reference_mean, signed), interpolation="nearest")
    axes[-1].set_title("reference", fontsize=8)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    return figure_png(fig, dpi=72)
