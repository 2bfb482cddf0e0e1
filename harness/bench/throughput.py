"""Render throughput of both engines side by side, in one process: the same scene file, sampler, resolution
and samples per pixel, render time only (scene load, BVH build and Mitsuba's JIT compilation excluded: one
warm-up render each first), medians of several runs. This separates per-sample cost from convergence.

Rays per second count the rays our integrator traced (camera plus shadow or occlusion rays); Mitsuba's
`direct` traces the same number for these integrators (one emitter sample per light, one BSDF-free
occlusion ray), so the same count is used for both.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from harness.images.suite import SCENES_DIR
from harness.engines.mitsuba_scene import load_scene

#: (scene, integrator, resolution, spp): the issue's four cases.
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

    def median(self, engine: str) -> float:
        return float(np.median(self.seconds[engine]))

    def ratio(self) -> float:
        """Mitsuba's median render time over ours: above 1, ours is faster per sample."""
        return self.median("mitsuba") / self.median("mcval")

    def to_json(self) -> dict:
        samples = self.resolution ** 2 * self.spp
        return {"scene": self.scene, "integrator": self.integrator, "resolution": self.resolution, "spp": self.spp,
                "sampler": self.sampler, "seconds": self.seconds, "rays": self.rays,
                "median_seconds": {e: self.median(e) for e in self.seconds},
                "samples_per_second": {e: samples / self.median(e) for e in self.seconds},
                "rays_per_second": {e: self.rays / self.median(e) for e in self.seconds},
                "mitsuba_over_ours": self.ratio()}


def _ours(scene: str, integrator: str, res: int, spp: int, sampler: str, seed: int) -> tuple[float, int]:
    import mcval_renderer
    out = mcval_renderer.render(scene, spp=spp, seed=seed, integrator=integrator, params={"res": str(res)},
                                sampler=sampler)
    s = out["stats"]
    return s["render_seconds"], s["camera_rays"] + s["shadow_rays"]


def measure(scene_name: str, integrator: str, res: int, spp: int, runs: int = 3, sampler: str = "independent",
            variant: str = "llvm_ad_rgb") -> Throughput:
    """Both engines on one case: a warm-up render each, then `runs` alternating timed renders."""
    import drjit as dr
    import mitsuba as mi
    if mi.variant() != variant:
        mi.set_variant(variant)
    scene = str(SCENES_DIR / f"{scene_name}.xml")
    loaded = load_scene(scene, integrator, res=str(res))

    def mitsuba(seed: int) -> float:
        start = time.perf_counter()
        image = mi.render(loaded, spp=spp, seed=seed)
        dr.eval(image)
        dr.sync_thread()
        return time.perf_counter() - start

    _ours(scene, integrator, res, spp, sampler, 0)
    mitsuba(0)
    seconds: dict[str, list[float]] = {"mcval": [], "mitsuba": []}
    rays = 0
    for run in range(1, runs + 1):
        t, rays = _ours(scene, integrator, res, spp, sampler, run)
        seconds["mcval"].append(t)
        seconds["mitsuba"].append(mitsuba(run))
    return Throughput(scene_name, integrator, res, spp, sampler, seconds, rays)


if __name__ == "__main__":
    import sys
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    print(f"{'case':<28} {'ours s':>8} {'mitsuba s':>10} {'mitsuba/ours':>13} {'ours Mrays/s':>13}")
    for case in CASES:
        r = measure(*case, runs=runs)
        print(f"{case[0]}:{case[1]} {case[2]}² {case[3]}spp".ljust(28),
              f"{r.median('mcval'):8.3f} {r.median('mitsuba'):10.3f} {r.ratio():13.2f} "
              f"{r.rays / r.median('mcval') / 1e6:13.1f}")
