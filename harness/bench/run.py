"""The whole benchmark: ladders for every case and engine, the seed document's settings, ray rates."""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from harness.bench.ladder import LADDER, RUNS, Curve, run_ladder
from harness.engines.base import Engine
from harness.images.suite import SCENES_DIR, ImageCase
from harness.images.references import load_reference, render_reference

#: The seed document's own figures: its simple integrator at 768x768 and 32 spp, its AO at 768x768
#: and 512 spp, both on a ~0.5M-triangle bust (seconds).
SEED_SETTINGS = {"simple": {"spp": 32, "seed_seconds": 14.5}, "ao": {"spp": 512, "seed_seconds": 360.0}}
SEED_RESOLUTION = 768


@dataclass
class CaseBench:
    case: ImageCase
    curves: dict[str, Curve]
    reference_mean: np.ndarray

    def efficiency_ratio(self, ours: str = "mcval", other: str = "mitsuba") -> float:
        if ours not in self.curves or other not in self.curves:
            return float("nan")
        return self.curves[ours].efficiency() / self.curves[other].efficiency()

    def to_json(self) -> dict:
        return {"integrator": self.case.integrator, "scene": self.case.scene,
                "efficiency_ratio": self.efficiency_ratio(),
                "slope": {k: c.fit("spp")[0] for k, c in self.curves.items()},
                "seconds": {k: float(np.median(c.steps[-1].seconds)) for k, c in self.curves.items()},
                "efficiency": {k: c.efficiency() for k, c in self.curves.items()},
                "time_to_target": {k: c.time_to() for k, c in self.curves.items()},
                "first_seconds": {k: c.first_seconds for k, c in self.curves.items()},
                "curves": [c.to_json() for c in self.curves.values()]}


def run_bench(cases: list[ImageCase], engines: list[Engine], reference_engine: Engine, seed: int = 0,
              ladder=LADDER, runs: int = RUNS, on_step: Callable[[str], None] | None = None) -> list[CaseBench]:
    """Every case with every engine, one render at a time."""
    out = []
    for case in cases:
        reference, _ = load_reference(case, reference_engine)
        if reference is None:
            reference = render_reference(case, reference_engine)
        curves = {e.name: run_ladder(e, case, reference, seed, ladder, runs, on_step) for e in engines}
        out.append(CaseBench(case, curves, reference.summary.pixel.mean))
    return out


def seed_comparison(ours: Engine, runs: int = 3, on_step: Callable[[str], None] | None = None) -> dict:
    """Our render seconds on the high-poly scene at the seed document's settings (medians of `runs`)."""
    scene = str(SCENES_DIR / "highpoly.xml")
    out = {}
    for integrator, setting in SEED_SETTINGS.items():
        times = []
        for run in range(runs):
            result = ours.render(scene, integrator, setting["spp"], 1, run, {"res": str(SEED_RESOLUTION)})
            times.append(result.seconds["render"])
            if on_step:
                on_step(f"seed settings: {integrator} run {run + 1}/{runs}: {times[-1]:.1f} s")
        out[integrator] = {"spp": setting["spp"], "resolution": SEED_RESOLUTION, "seconds": float(np.median(times)),
                           "runs": times, "seed_seconds": setting["seed_seconds"]}
    return out


def ray_rates(path: Path | None) -> dict | None:
    """The ray-throughput figures bench/ray_throughput.cpp wrote, if any."""
    if path is None or not Path(path).exists():
        return None
    return json.loads(Path(path).read_text())

