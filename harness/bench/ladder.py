"""Speed against error: each engine renders a ladder of sample counts, several runs per step, and
its error against the high-sample reference is tracked against samples and against seconds."""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from harness.engines.base import Engine
from harness.images.suite import ImageCase
from harness.comparison.metrics import RELMSE_EPSILON, flip_map
from harness.images.references import RESOLUTION, Reference
from harness.integrators import entry

#: Samples per pixel of the ladder, and independent runs per step.
LADDER = (1, 2, 4, 8, 16, 32, 64, 128, 256)
RUNS = 3
#: The relMSE at which "time to reach" is read off the fitted curve.
TARGET_RELMSE = 1e-3


def relmse(image: np.ndarray, reference: Reference) -> float:
    """relMSE against the reference mean, minus the part the reference's own noise contributes."""
    r = reference.summary.pixel.mean
    excess = (image - r) ** 2 - reference.summary.pixel.var_of_mean
    return float(np.mean(excess / (r**2 + RELMSE_EPSILON)))


@dataclass
class Step:
    spp: int
    seconds: list[float]          # render seconds per run (what they include: see Curve.timing)
    relmse: list[float]
    flip: list[float]


@dataclass
class Curve:
    """One engine's ladder on one case."""

    engine: str
    timing: str                   # what `seconds` includes
    steps: list[Step]
    first_seconds: float          # the very first render (with JIT compilation for llvm variants)
    images: dict[int, np.ndarray] = field(default_factory=dict, repr=False)

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        spp = np.array([s.spp for s in self.steps], float)
        sec = np.array([np.median(s.seconds) for s in self.steps])
        err = np.array([np.median(s.relmse) for s in self.steps])
        return spp, sec, err

    def fit(self, against: str = "spp") -> tuple[float, float]:
        """(slope, intercept) of log relMSE against log spp or log seconds, over steps with relMSE > 0."""
        spp, sec, err = self.arrays()
        x = spp if against == "spp" else sec
        ok = (err > 0) & (x > 0)
        if ok.sum() < 2:
            return float("nan"), float("nan")
        slope, intercept = np.polyfit(np.log(x[ok]), np.log(err[ok]), 1)
        return float(slope), float(intercept)

    def efficiency(self, only: set[int] | None = None) -> float:
        """1 / (relMSE * seconds) over the steps of 16 spp and more (where the fit is linear; all steps for
        a shorter ladder): the geometric mean over steps of 1 / (mean relMSE of the runs x median seconds).
        The mean estimates the MSE (a median of a few skewed squared errors is noisy and biased low), and
        every step counts: the median of five per-step values swung a ratio of two statistically identical
        estimators by 30 % (grazing_light simple, one step's errors 1.8 apart). `only`: just these steps,
        so two curves are compared where both rendered (a stratified curve's efficiency grows with spp,
        and a rounding sampler skips steps)."""
        spp = np.array([s.spp for s in self.steps], float)
        sec = np.array([np.median(s.seconds) for s in self.steps])
        err = np.array([np.mean(s.relmse) for s in self.steps])
        if only is not None:
            keep = np.isin(spp, sorted(only))
            spp, sec, err = spp[keep], sec[keep], err[keep]
        if not len(spp):
            return float("nan")
        ok = ((spp >= 16) | (spp.max() < 16)) & (err > 0)
        return float(np.exp(np.mean(-np.log(err[ok] * sec[ok])))) if ok.any() else float("nan")

    def time_to(self, target: float = TARGET_RELMSE) -> float:
        """Seconds to reach `target` relMSE on the fitted relMSE-against-seconds line."""
        slope, intercept = self.fit("seconds")
        if not np.isfinite(slope) or slope >= 0:
            return float("inf")
        return float(np.exp((np.log(target) - intercept) / slope))

    def to_json(self) -> dict:
        return {"engine": self.engine, "timing": self.timing, "first_seconds": self.first_seconds,
                "slope": self.fit("spp")[0], "slope_seconds": self.fit("seconds")[0],
                "efficiency": self.efficiency(), "time_to_target": self.time_to(),
                "steps": [{"spp": s.spp, "seconds": s.seconds, "relmse": s.relmse, "flip": s.flip}
                          for s in self.steps]}


def run_ladder(engine: Engine, case: ImageCase, reference: Reference, seed: int, ladder=LADDER,
               runs: int = RUNS, on_step: Callable[[str], None] | None = None) -> Curve:
    """Render `case` at every step of the ladder, `runs` times each, one job at a time. A step's runs
    are rendered back to back and their errors computed after them: FLIP's OpenMP threads and the
    cache they sweep, between two renders, slowed mcval's renders by 20-40 % at 128^2 (32 spp: 5.8 ms back to
    back, 7-10 ms with FLIP between), which timed the harness rather than the engine."""
    params = {"res": str(RESOLUTION)}
    signed = entry(case.integrator).signed
    steps, images, first = [], {}, None
    for spp in ladder:
        if not engine.renders_exactly(spp):
            continue  # it would render more samples than the step says
        step, rendered = Step(spp, [], [], []), []
        for run in range(runs):
            start = time.perf_counter()
            result = engine.render(str(case.path), case.integrator, spp, 1, seed + 7919 * run + spp, params)
            wall = time.perf_counter() - start
            if first is None:
                first = wall
            step.seconds.append(result.seconds.get("render", wall))
            rendered.append(result.batches[0])
        for image in rendered:
            step.relmse.append(relmse(image, reference))
            step.flip.append(flip_map(image, reference.summary.pixel.mean, signed)[1])
        images[spp] = rendered[0]
        steps.append(step)
        if on_step:
            on_step(f"{engine.label or engine.name} {case.key} {spp} spp")
    if first is None:
        raise ValueError(f"{engine.label or engine.name} renders none of the ladder's sample counts "
                         f"({', '.join(map(str, ladder))} spp) exactly: its sampler rounds them; "
                         "--same-sampler gives both engines Mitsuba's independent sampler")
    timing = getattr(engine, "render_timing", "render seconds")
    return Curve(engine.label or engine.name, timing, steps, float(first), images)
