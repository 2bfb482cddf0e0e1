"""Render throughput of both engines side by side, in one process: the same scene file, sampler, resolution
and samples per pixel, render time only (scene load, BVH build and Mitsuba's JIT compilation excluded: each timed
render follows a pause and then an untimed one of the same engine), medians of several runs. This separates per-sample cost from convergence.

Rays per second divide the same count for both engines: the rays our integrator traced (camera rays plus the
shadow or occlusion rays of front-facing hits), i.e. the work of our estimate. Mitsuba's `direct` traces about as
many for simple (one emitter sample, no BSDF sample), but for ao it also traces a BSDF-sampled ray per hit (its
MIS), so its own count there is up to 1.5 times this one.

Run alone: `python -m harness.bench.throughput [runs] [sampler]` prints the table (the renderer's Python module must be on
PYTHONPATH, as `make build` puts it in build/python).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from harness.images.suite import SCENES_DIR
from harness.engines.mitsuba import MitsubaEngine, load_mitsuba
from harness.engines.mitsuba_scene import MITSUBA_SAMPLER, load_scene
from harness.engines.ours import OurEngine
from harness.native import renderer_module

#: The two engines timed side by side, in process, by name (the keys of the figures).
OURS, MITSUBA = OurEngine.name, MitsubaEngine.name
#: Ours as `images` and `validate` run it: in its `render --serve` worker, the call's wall clock less the scene
#: load and BVH build the renderer reports (excluded for every engine), so with the request, the images written
#: and read, and the thread pool's wake-up.
WORKER = f"{OURS} worker"

#: Seconds to wait before an engine's renders, so that the other engine's threads have stopped spinning.
QUIET_SECONDS = 0.25

#: (scene, integrator, resolution, spp): the four cases timed side by side.
CASES = (("highpoly", "simple", 768, 32), ("highpoly", "ao", 768, 16),
         ("cornell", "simple", 128, 64), ("cornell", "ao", 128, 64))


@dataclass
class Throughput:
    scene: str
    integrator: str
    resolution: int
    spp: int
    sampler: str
    seconds: dict[str, list[float]]   # engine -> render seconds per run
    rays: int                         # rays our renderer traced in one render
    #: Samples per pixel Mitsuba rendered: its sampler may round `spp` up (ldsampler makes 32 into 64).
    mitsuba_spp: int = 0

    def rendered_spp(self, engine: str) -> int:
        return self.mitsuba_spp or self.spp if engine == MITSUBA else self.spp

    def median(self, engine: str) -> float:
        return float(np.median(self.seconds[engine]))

    def ratio(self, ours: str = OURS) -> float:
        """Mitsuba's render time over ours (`ours`: OURS in process, or WORKER), per sample (the same as per
        render unless Mitsuba's sampler rounded the count), taken run by run (each round renders ours, then
        Mitsuba) and the median of those: the machine's drift between rounds cancels within a round. Above
        1, ours is faster per sample."""
        per_round = [(m / self.rendered_spp(MITSUBA)) / (o / self.spp)
                     for o, m in zip(self.seconds[ours], self.seconds[MITSUBA])]
        return float(np.median(per_round))

    def to_json(self) -> dict:
        samples = {e: self.resolution ** 2 * self.rendered_spp(e) for e in self.seconds}
        # Rays of the same estimate per sample: ours scaled by the samples each engine took.
        rays = {e: self.rays * self.rendered_spp(e) / self.spp for e in self.seconds}
        return {"scene": self.scene, "integrator": self.integrator, "resolution": self.resolution, "spp": self.spp,
                "spp_rendered": {e: self.rendered_spp(e) for e in self.seconds},
                "sampler": self.sampler, "seconds": self.seconds, "rays": self.rays,
                "median_seconds": {e: self.median(e) for e in self.seconds},
                "samples_per_second": {e: samples[e] / self.median(e) for e in self.seconds},
                "rays_per_second": {e: rays[e] / self.median(e) for e in self.seconds}, "ray_count": "ours",
                "mitsuba_over_ours": self.ratio(),
                **({"mitsuba_over_ours_worker": self.ratio(WORKER)} if WORKER in self.seconds else {})}


def _ours(scene: str, integrator: str, res: int, spp: int, sampler: str, seed: int) -> tuple[float, int]:
    out = renderer_module().render(scene, spp=spp, seed=seed, integrator=integrator, params={"res": str(res)},
                                sampler=sampler)
    s = out["stats"]
    return s["render_seconds"], s["camera_rays"] + s["shadow_rays"]


def measure(scene_name: str, integrator: str, res: int, spp: int, runs: int = 3, sampler: str = "independent",
            variant: str = "llvm_ad_rgb") -> Throughput:
    """Both engines on one case with `sampler` (ours; Mitsuba gets its plugin of that name or the closest,
    MITSUBA_SAMPLER): `runs` rounds, each an untimed then a timed render of ours in process, then in its worker
    (WORKER), then of Mitsuba."""
    import drjit as dr
    mi = load_mitsuba(variant)  # finds LLVM 19 for an llvm variant
    scene = str(SCENES_DIR / f"{scene_name}.xml")
    loaded = load_scene(scene, integrator, sampler=MITSUBA_SAMPLER.get(sampler, sampler), res=str(res))

    def mitsuba(seed: int) -> float:
        start = time.perf_counter()
        image = mi.render(loaded, spp=spp, seed=seed)
        dr.eval(image)
        dr.sync_thread()
        return time.perf_counter() - start

    worker = OurEngine(sampler=sampler)

    def in_worker(seed: int) -> float:
        out = worker.render(scene, integrator, spp, 1, seed, {"res": str(res)})
        return out.seconds["total"] - out.seconds["load"] - out.seconds["build"]

    seconds: dict[str, list[float]] = {OURS: [], WORKER: [], MITSUBA: []}
    rays = 0
    for run in range(1, runs + 1):
        # Each engine's timed render follows a pause longer than either engine keeps its threads spinning
        # after a render (ours 100 ms), then an untimed render of its own: so it meets neither the other
        # engine's threads still spinning nor its own asleep (waking a worker thread costs this machine
        # several ms, a third of a 128² render). Both engines are treated alike.
        time.sleep(QUIET_SECONDS)
        _ours(scene, integrator, res, spp, sampler, 1000 + run)
        t, rays = _ours(scene, integrator, res, spp, sampler, run)
        seconds[OURS].append(t)
        time.sleep(QUIET_SECONDS)
        in_worker(1000 + run)
        seconds[WORKER].append(in_worker(run))
        time.sleep(QUIET_SECONDS)
        mitsuba(1000 + run)
        seconds[MITSUBA].append(mitsuba(run))
    mitsuba_spp = loaded.sensors()[0].sampler().sample_count()  # as the renders set it
    return Throughput(scene_name, integrator, res, spp, sampler, seconds, rays, mitsuba_spp)
