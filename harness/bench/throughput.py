"""Render throughput of the tested and the reference engine side by side: the same scene file, sampler,
resolution and samples per pixel, render time only (scene load, BVH build and JIT compilation excluded: each
timed render follows a pause and then an untimed one of the same engine), medians of several runs. This separates
per-sample cost from convergence.

The tested engine is timed as the bench renders it (in this process where it can) and, where it renders in
another process when not asked otherwise (mcval's: its `render --serve` worker), there too (WORKER): the call's wall
clock less the scene load and BVH build it reports, so with the request, the images written and read, and the
thread pool's wake-up.

Rays per second divide the same count for both engines: the rays the tested engine traced
(RenderResult.rays: camera rays plus the shadow or occlusion rays of front-facing hits), i.e. the work of its
estimate. Mitsuba's `direct` traces about as many for simple (one emitter sample, no BSDF sample), but for ao it
also traces a BSDF-sampled ray per hit (its MIS), so its own count there is up to 1.5 times this one. For `direct`
both trace an emitter sample's shadow ray and a BSDF sample's ray per hit.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from harness.engines.base import Engine
from harness.images.suite import SCENES_DIR

#: The figures' keys: the tested engine in process, in its worker, and the reference engine.
TESTED, WORKER, REFERENCE = "tested", "tested worker", "reference"

#: Seconds to wait before an engine's renders, so that the other engine's threads have stopped spinning.
QUIET_SECONDS = 0.25

#: (scene, integrator, resolution, spp): the cases timed side by side.
CASES = (("highpoly", "simple", 768, 32), ("highpoly", "ao", 768, 16), ("highpoly", "direct", 768, 16),
         ("highpoly", "path", 768, 16), ("cornell", "simple", 128, 64), ("cornell", "ao", 128, 64),
         ("cornell", "direct", 128, 64), ("cornell", "path", 128, 64))


@dataclass
class Throughput:
    scene: str
    integrator: str
    resolution: int
    spp: int
    sampler: str
    seconds: dict[str, list[float]]   # TESTED, WORKER, REFERENCE -> render seconds per run
    rays: int | None                  # rays the tested engine traced in one render, where it counts them
    engines: dict[str, str]           # TESTED, REFERENCE -> the engine's name

    def median(self, engine: str) -> float:
        return float(np.median(self.seconds[engine]))

    def ratio(self, tested: str = TESTED) -> float:
        """The reference's render time over the tested engine's (`tested`: TESTED in process, or WORKER), taken
        run by run (each round renders the tested engine, then the reference) and the median of those: the
        machine's drift between rounds cancels within a round. Above 1, the tested engine is faster."""
        return float(np.median([r / t for t, r in zip(self.seconds[tested], self.seconds[REFERENCE])]))

    def to_json(self) -> dict:
        samples = self.resolution ** 2 * self.spp
        return {"scene": self.scene, "integrator": self.integrator, "resolution": self.resolution, "spp": self.spp,
                "sampler": self.sampler, "engines": self.engines, "seconds": self.seconds, "rays": self.rays,
                "median_seconds": {e: self.median(e) for e in self.seconds},
                "samples_per_second": {e: samples / self.median(e) for e in self.seconds},
                **({"rays_per_second": {e: self.rays / self.median(e) for e in self.seconds}, "ray_count": TESTED}
                   if self.rays is not None else {}),
                "reference_over_tested": self.ratio(),
                **({"reference_over_tested_worker": self.ratio(WORKER)} if WORKER in self.seconds else {})}


def _render_seconds(engine: Engine, scene: str, integrator: str, res: int, spp: int, seed: int):
    """(render seconds, the result) of one render; the load and build it reports are not counted."""
    out = engine.render(scene, integrator, spp, 1, seed, {"res": str(res)})
    return out.seconds["render"], out


def measure(scene_name: str, integrator: str, res: int, spp: int, tested: Engine, reference: Engine,
            worker: Engine | None = None, runs: int = 3, sampler: str = "independent") -> Throughput:
    """The engines on one case (each made with `sampler`, the tested one to render in this process where it can;
    `worker`: the tested engine as `images` runs it, timed too): `runs` rounds, each an untimed then a timed
    render of the tested engine, then of `worker`, then of the reference."""
    scene = str(SCENES_DIR / f"{scene_name}.xml")

    def in_worker(seed: int) -> float:
        out = worker.render(scene, integrator, spp, 1, seed, {"res": str(res)})
        return out.seconds["total"] - out.seconds.get("load", 0.0) - out.seconds.get("build", 0.0)

    seconds: dict[str, list[float]] = {TESTED: [], **({WORKER: []} if worker else {}), REFERENCE: []}
    rays = None
    for run in range(1, runs + 1):
        # Each engine's timed render follows a pause longer than either engine keeps its threads spinning
        # after a render (mcval's 100 ms), then an untimed render of its own: so it meets neither the other
        # engine's threads still spinning nor its own asleep (waking a worker thread costs this machine
        # several ms, a third of a 128² render). Both engines are treated alike.
        time.sleep(QUIET_SECONDS)
        _render_seconds(tested, scene, integrator, res, spp, 1000 + run)
        t, out = _render_seconds(tested, scene, integrator, res, spp, run)
        seconds[TESTED].append(t)
        rays = out.rays
        if worker is not None:
            time.sleep(QUIET_SECONDS)
            in_worker(1000 + run)
            seconds[WORKER].append(in_worker(run))
        time.sleep(QUIET_SECONDS)
        _render_seconds(reference, scene, integrator, res, spp, 1000 + run)
        seconds[REFERENCE].append(_render_seconds(reference, scene, integrator, res, spp, run)[0])
    return Throughput(scene_name, integrator, res, spp, sampler, seconds, rays,
                      {TESTED: tested.label or tested.name, REFERENCE: reference.label or reference.name})
