"""The analytic engine: closed-form radiance on one plane, integrated over each pixel by jittered
camera rays (numpy). Its only noise is the pixel footprint; its light transport is exact. Each integrator's
closed form is in its entry (harness/integrators/<name>.py, `analytic`); one without has none here.
"""
from __future__ import annotations

import time

import numpy as np

from harness.engines.analytic_scene import NotAnalytic, load_plane_scene
from harness.engines.base import Engine, RenderResult
from harness.integrators import entry


def _shade(scene, integrator: str, p: np.ndarray, normal: np.ndarray) -> np.ndarray:
    form = entry(integrator).analytic
    if form is None:
        raise NotAnalytic(f"integrator {integrator} has no closed form ({entry(integrator).source})")
    return form.shade(scene, p, normal)


class AnalyticEngine(Engine):
    """Closed forms for one-plane scenes; `render` raises NotAnalytic for any other scene."""

    name = "analytic"

    def version(self) -> str:
        return "analytic (closed form, numpy pixel integration)"

    @staticmethod
    def supports(scene: str, params: dict[str, str] | None = None, integrator: str | None = None) -> bool:
        """Whether `scene` is a one-plane scene (and `integrator`, if given, has a closed form)."""
        if integrator is not None and entry(integrator).analytic is None:
            return False
        try:
            load_plane_scene(scene, params)
        except NotAnalytic:
            return False
        return True

    def render(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None) -> RenderResult:
        """Seconds: "load" (parse) and "render" (all batches)."""
        start = time.perf_counter()
        s = load_plane_scene(scene, params)
        seconds = {"load": time.perf_counter() - start}
        inv_plane = np.linalg.inv(s.plane)
        normal = np.linalg.inv(s.plane[:3, :3]).T @ np.array([0.0, 0.0, 1.0])
        normal /= np.linalg.norm(normal)
        plane_point = s.plane[:3, 3]
        aspect = s.width / s.height
        rng = np.random.default_rng([seed, 0xA11])
        ys, xs = np.mgrid[0 : s.height, 0 : s.width]
        images = []
        for _ in range(batches):
            acc = np.zeros((s.height, s.width, 3))
            for _ in range(spp):
                fx = (xs + rng.random(xs.shape)) / s.width
                fy = (ys + rng.random(ys.shape)) / s.height
                local = np.stack([(1 - 2 * fx) * s.tan_half_x, (1 - 2 * fy) * s.tan_half_x / aspect,
                                  np.ones_like(fx)], axis=-1)
                local /= np.linalg.norm(local, axis=-1, keepdims=True)
                d = local @ s.to_world.T
                denom = d @ normal
                with np.errstate(divide="ignore", invalid="ignore"):
                    t = ((plane_point - s.origin) @ normal) / denom
                p = s.origin + t[..., None] * d
                uv = p @ inv_plane[:3, :3].T + inv_plane[:3, 3]
                # Hit: in front of the near plane, inside [-1,1]^2, seen from the front side.
                hit = (t * local[..., 2] > s.near_clip) & (denom < 0) & np.all(np.abs(uv[..., :2]) <= 1, axis=-1)
                acc += np.where(hit[..., None], _shade(s, integrator, p, normal), 0.0)
            images.append((acc / spp).astype(np.float32))
        seconds["render"] = time.perf_counter() - start - seconds["load"]
        seconds["total"] = time.perf_counter() - start
        return RenderResult(self.name, str(scene), integrator, spp, seed, np.stack(images), seconds)


__all__ = ["AnalyticEngine", "NotAnalytic"]
