"""The whole benchmark: ladders for every case and engine, the seed document's settings, ray rates."""
from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from harness.bench.ladder import LADDER, RUNS, Curve, run_ladder
from harness.bench.throughput import QUIET_SECONDS
from harness.distributed.bundle import Bundle
from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.base import Engine
from harness.engines.registry import DEFAULT_REFERENCE, DEFAULT_TEST
from harness.images.case_task import on_files, share_scene_bundles
from harness.images.suite import SCENES_DIR, ImageCase
from harness.bench.truth import bench_truth

#: The seed document's own figures: its simple integrator at 768x768 and 32 spp, its AO at 768x768
#: and 512 spp, both on a ~0.5M-triangle bust (seconds).
SEED_SETTINGS = {"simple": {"spp": 32, "seed_seconds": 14.5}, "ao": {"spp": 512, "seed_seconds": 360.0}}
SEED_RESOLUTION = 768


#: The sampler both engines run with for the engine comparison (like for like). The samplers each engine is
#: benchmarked with, and those its best is chosen from, are the engine's own (Engine.samplers, best_samplers).
SAME_SAMPLER = "independent"


def _sampler_of(label: str | None) -> str | None:
    """The sampler in a curve label ("mitsuba/ldsampler" -> "ldsampler"); "scene" for a bare engine name."""
    return None if label is None else label.split("/", 1)[1] if "/" in label else "scene"


@dataclass
class CaseBench:
    """One case's curves, keyed by engine label ("mcval/sobol", "mitsuba/independent", or a bare engine name
    when the scene's own sampler was used)."""

    case: ImageCase
    curves: dict[str, Curve]
    reference_mean: np.ndarray
    truth: str = ""  # what the errors are measured against (bench_truth)
    tested: str = DEFAULT_TEST        # the engine under test, and the one its efficiency is compared with
    reference: str = DEFAULT_REFERENCE
    #: Per engine, the samplers its best curve is chosen from (by measured efficiency on the case:
    #: Engine.best_samplers). An engine with none of them run falls back on its best curve of any sampler.
    best: dict[str, tuple[str, ...]] = field(default_factory=dict)

    def _pick(self, engine: str, sampler: str | None) -> str | None:
        """The label of `engine` with `sampler` (None: its most efficient best sampler), if it was run."""
        mine = [k for k in self.curves if k.split("/")[0] == engine]
        if sampler is not None:
            mine = [k for k in mine if k.split("/")[-1] == sampler or k == engine]
        else:
            mine = [k for k in mine if k.split("/")[-1] in self.best.get(engine, ())] or mine
        finite = [k for k in mine if self.curves[k].efficiency() == self.curves[k].efficiency()]
        return max(finite, key=lambda k: self.curves[k].efficiency()) if finite else (mine[0] if mine else None)

    def comparison(self, sampler: str | None, tested: str | None = None, other: str | None = None) -> dict:
        """Efficiency of the tested engine over `other`: both with `sampler` (the engine comparison), or each
        with its most efficient stratified sampler (sampler None: what a user gets), over the steps both
        rendered. Names the curves compared (keys "tested" and "reference" in results.json)."""
        tested, other = tested or self.tested, other or self.reference
        a, b = self._pick(tested, sampler), self._pick(other, sampler)
        ratio = float("nan")
        if a and b:
            common = {s.spp for s in self.curves[a].steps} & {s.spp for s in self.curves[b].steps}
            ratio = self.curves[a].efficiency(common) / self.curves[b].efficiency(common)
        # An engine not run with that sampler has no curve: its NaN is not a lack of signal.
        missing = [name for name, label in ((tested, a), (other, b)) if not label]
        return {"ratio": ratio, "tested": a, "reference": b, "missing": missing,
                "tested_sampler": _sampler_of(a), "reference_sampler": _sampler_of(b)}

    def efficiency_ratio(self, tested: str | None = None, other: str | None = None) -> float:
        """The like-for-like ratio (both engines with SAME_SAMPLER)."""
        return self.comparison(SAME_SAMPLER, tested, other)["ratio"]

    def to_json(self) -> dict:
        return {"integrator": self.case.integrator, "scene": self.case.scene, "truth": self.truth,
                "efficiency_ratio": self.efficiency_ratio(),
                "efficiency_ratio_same_sampler": self.comparison(SAME_SAMPLER),
                "efficiency_ratio_best": self.comparison(None),
                "slope": {k: c.fit("spp")[0] for k, c in self.curves.items()},
                "seconds": {k: float(np.median(c.steps[-1].seconds)) for k, c in self.curves.items()},
                "efficiency": {k: c.efficiency() for k, c in self.curves.items()},
                "time_to_target": {k: c.time_to() for k, c in self.curves.items()},
                "first_seconds": {k: c.first_seconds for k, c in self.curves.items()},
                "curves": [c.to_json() for c in self.curves.values()]}


def run_bench(cases: list[ImageCase], engines: list[Engine], reference_engine: Engine, seed: int = 0,
              ladder=LADDER, runs: int = RUNS, on_step: Callable[[str], None] | None = None,
              executor: Executor | None = None, on_status: Callable[[Status], None] | None = None) -> list[CaseBench]:
    """Every case with every engine. Each case is one task: its engines' ladders one render at a time on
    one worker, so the engines it compares share a machine (`executor`: default here, one after another;
    `on_step` reports each step when the case runs in this process)."""
    executor = executor or SerialExecutor()
    bundles = share_scene_bundles(executor, cases, (*engines, reference_engine))
    tasks = [Task(case.key, bench_case, (case, engines, reference_engine, seed, ladder, runs,
                                         None if executor.ships_files else on_step, bundles.get(case.scene)))
             for case in cases]
    out = []
    for task, outcome in zip(tasks, executor.run(tasks, on_status)):
        if not outcome.ok:
            raise RuntimeError(f"bench {task.key}: {outcome.error}")
        out.append(outcome.value)
    return out


def bench_case(case: ImageCase, engines: list[Engine], reference_engine: Engine, seed: int, ladder, runs: int,
               on_step: Callable[[str], None] | None = None, bundle: Bundle | None = None) -> CaseBench:
    """One case's ladders, every engine in turn (with a bundle: on the bundle's copy of the files)."""
    local = on_files(case, bundle)
    reference, truth = bench_truth(local, reference_engine, max(ladder))
    curves = {}
    for e in engines:
        time.sleep(QUIET_SECONDS)  # the previous engine's threads have stopped spinning
        curves[e.label or e.name] = run_ladder(e, local, reference, seed, ladder, runs, on_step)
    # The tested engine's efficiency is compared with the next engine run (Mitsuba as shipped, by default), else
    # with the reference.
    compared = next((e.name for e in engines[1:] if e.name != engines[0].name), reference_engine.name)
    return CaseBench(case, curves, reference.summary.pixel.mean, truth, engines[0].name, compared,
                     {e.name: e.best_samplers for e in engines})


def _render_seconds(engine: Engine, scene: str, integrator: str, spp: int, seed: int) -> float:
    """Render time of `spp` samples per pixel at the seed resolution, in passes of at most the engine's
    `pass_spp` (a wavefront engine: 768^2 x 512 samples at once would not fit in memory)."""
    params = {"res": str(SEED_RESOLUTION)}
    if engine.pass_spp is None:
        return engine.render(scene, integrator, spp, 1, seed, params).seconds["render"]
    passes = max(1, spp // engine.pass_spp)
    return sum(engine.render(scene, integrator, spp // passes, 1, seed * 1000 + k, params).seconds["render"]
               for k in range(passes))


def seed_comparison(tested: Engine, runs: int = 3, on_step: Callable[[str], None] | None = None,
                    reference: Engine | None = None) -> dict:
    """Render seconds on the high-poly scene at the seed document's settings (medians of `runs`), the tested
    engine's and, if given, the reference's beside it (after one warm-up render, which JIT-compiles an llvm
    variant)."""
    scene = str(SCENES_DIR / "highpoly.xml")
    out = {}
    for integrator, setting in SEED_SETTINGS.items():
        entry = {"spp": setting["spp"], "resolution": SEED_RESOLUTION, "seed_seconds": setting["seed_seconds"]}
        for engine in [tested] + ([reference] if reference else []):
            if engine is reference:
                engine.render(scene, integrator, min(setting["spp"], engine.pass_spp or setting["spp"]), 1, 0,
                              {"res": str(SEED_RESOLUTION)})  # warm-up
            times = []
            for run in range(runs):
                times.append(_render_seconds(engine, scene, integrator, setting["spp"], run))
                if on_step:
                    on_step(f"seed settings: {engine.label or engine.name} {integrator} run {run + 1}/{runs}: "
                            f"{times[-1]:.1f} s")
            if engine is tested:
                entry.update(seconds=float(np.median(times)), runs=times)
            else:
                entry.update(reference_seconds=float(np.median(times)), reference_runs=times,
                             reference=engine.version())
        out[integrator] = entry
    return out


def ray_rates(path: Path | None) -> dict | None:
    """The ray-throughput figures bench/ray_throughput.cpp wrote, if any."""
    if path is None or not Path(path).exists():
        return None
    return json.loads(Path(path).read_text())

