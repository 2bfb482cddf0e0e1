"""The analytic engine: closed-form radiance on one plane, or on a sphere resting on it, integrated over each
pixel by jittered camera rays (numpy). Its noise is the pixel footprint, and where a closed form is a
probability (ao's visibility) one draw of it per ray, as the renderers' estimators have; the expectation is exact.
Each integrator's closed form is in its entry (harness/integrators/<name>.py, `analytic`), with the scene
kinds it covers; one without has none here. The sphere's geometry and visibility: analytic_sphere.py.
"""
from __future__ import annotations

import dataclasses
import time

import numpy as np

from harness.closed_forms.plane_scene import NotAnalytic, PlaneScene, load_plane_scene
from harness.closed_forms.sphere import check_resting, hit_sphere
from harness.closed_forms.vectors import norm
from harness.engines.base import Engine, RenderResult
from harness.integrators import entry

#: Pixel samples traced per pass (a few MB per array).
CHUNK_PIXELS = 1 << 17


def load(scene: str, params: dict[str, str] | None = None, integrator: str | None = None) -> PlaneScene:
    """The scene, if the engine has its image (with `integrator`'s closed form, if given); else NotAnalytic."""
    s = load_plane_scene(scene, params)
    if s.sphere is not None:
        check_resting(s)
    if integrator is not None:
        form = entry(integrator).analytic
        if form is None:
            raise NotAnalytic(f"integrator {integrator} has no closed form ({entry(integrator).source})")
        if s.kind not in form.scenes:
            raise NotAnalytic(f"integrator {integrator}'s closed form covers {', '.join(form.scenes)}, "
                              f"not {s.kind}")
    return s


class AnalyticEngine(Engine):
    """Closed forms for a lone plane and a sphere resting on it; `render` raises NotAnalytic otherwise."""

    name = "analytic"

    @staticmethod
    def samples_for(integrator: str, spp: int) -> int:
        """Samples per pixel to render where ours renders `spp`: four times as many where the closed form is
        sampled (its noise then predicts what ours may miss), as many where it is noiseless per ray."""
        return 4 * spp if entry(integrator).analytic.sample is not None else spp

    def version(self) -> str:
        return "analytic (closed form, numpy pixel integration)"

    @staticmethod
    def supports(scene: str, params: dict[str, str] | None = None, integrator: str | None = None) -> bool:
        """Whether `scene` is a lone plane or a sphere resting on one (and `integrator`, if given, has a
        closed form for that kind of scene)."""
        try:
            load(scene, params, integrator)
        except NotAnalytic:
            return False
        return True

    def render(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None) -> RenderResult:
        """Seconds: "load" (parse) and "render" (all batches)."""
        start = time.perf_counter()
        s = load(scene, params, integrator)
        form = entry(integrator).analytic
        rng = np.random.default_rng([seed, 0xA11])

        def shade(view: PlaneScene, p: np.ndarray, n: np.ndarray) -> np.ndarray:
            if form.sample is None:
                return form.shade(view, p, n)
            return form.sample(view, p, n, rng.random(p.shape[:-1] + (1,)))

        seconds = {"load": time.perf_counter() - start}
        inv_plane = np.linalg.inv(s.plane)
        normal = np.linalg.inv(s.plane[:3, :3]).T @ np.array([0.0, 0.0, 1.0])
        normal /= np.linalg.norm(normal)
        plane_point = s.plane[:3, 3]
        aspect = s.width / s.height
        ys, xs = np.mgrid[0 : s.height, 0 : s.width]
        floor_view = dataclasses.replace(s, surface="floor")
        sphere_view = dataclasses.replace(s, surface="sphere", reflectance=s.sphere.reflectance) if s.sphere else None
        # Samples are traced CHUNK_PIXELS pixel-samples at a time: whole arrays keep numpy's per-call cost small.
        chunk = max(1, CHUNK_PIXELS // (s.width * s.height))
        images = []
        for _ in range(batches):
            acc = np.zeros((s.height, s.width, 3))
            for first in range(0, spp, chunk):
                count = min(chunk, spp - first)
                fx = (xs + rng.random((count, *xs.shape))) / s.width
                fy = (ys + rng.random((count, *ys.shape))) / s.height
                local = np.stack([(1 - 2 * fx) * s.tan_half_x, (1 - 2 * fy) * s.tan_half_x / aspect,
                                  np.ones_like(fx)], axis=-1)
                local /= norm(local, keepdims=True)
                d = _transform(local, s.to_world)
                denom = d @ normal
                with np.errstate(divide="ignore", invalid="ignore"):
                    t = ((plane_point - s.origin) @ normal) / denom
                p = s.origin + t[..., None] * d
                uv = _transform(p, inv_plane[:3, :3]) + inv_plane[:3, 3]
                # Hit: between the clip planes, inside [-1,1]^2, seen from the front side.
                hit = (_clipped(s, t, local) & (denom < 0) & (np.abs(uv[..., 0]) <= 1) & (np.abs(uv[..., 1]) <= 1))
                if s.sphere is None:
                    acc += np.where(hit[..., None], shade(s, p, normal), 0.0).sum(axis=0)
                    continue
                ts = hit_sphere(s, s.origin, d)
                on_sphere = _clipped(s, ts, local) & (~hit | (ts < t))
                q = s.origin + np.where(np.isfinite(ts), ts, 0.0)[..., None] * d
                n = (q - s.sphere.center) / s.sphere.radius
                acc += np.where(on_sphere[..., None], shade(sphere_view, q, n),
                                np.where((hit & ~on_sphere)[..., None], shade(floor_view, p, normal), 0.0)).sum(axis=0)
            images.append((acc / spp).astype(np.float32))
        seconds["render"] = time.perf_counter() - start - seconds["load"]
        seconds["total"] = time.perf_counter() - start
        return RenderResult(self.name, str(scene), integrator, spp, seed, np.stack(images), seconds)


def _transform(v: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """matrix @ each (..., 3) vector, as one matrix product over the rows (numpy's stacked product of
    (..., 3) by (3, 3) takes four times as long)."""
    return (v.reshape(-1, 3) @ matrix.T).reshape(v.shape)


def _clipped(s: PlaneScene, t: np.ndarray, local: np.ndarray) -> np.ndarray:
    """Hits whose depth along the camera's axis lies between near_clip and far_clip."""
    with np.errstate(invalid="ignore"):
        depth = t * local[..., 2]
        return (depth > s.near_clip) & (depth < s.far_clip)


__all__ = ["AnalyticEngine", "NotAnalytic", "load"]
