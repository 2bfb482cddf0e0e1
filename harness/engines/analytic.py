"""The analytic engine: closed-form radiance on one plane, or on a sphere resting on it, integrated over each
pixel by jittered camera rays (numpy), and the one value of a furnace (harness/closed_forms/furnace.py). Its
noise is the pixel footprint, and where a closed form is a probability (ao's visibility) one draw of it per ray,
as the renderers' estimators have; the expectation is exact.
Each integrator's closed form is in its entry (harness/integrators/<name>.py, `analytic`), with the scene
kinds it covers; one without has none here. The sphere's geometry and visibility: analytic_sphere.py.
"""
from __future__ import annotations

import dataclasses
import time

import numpy as np

from harness.closed_forms.furnace import Furnace, load_furnace
from harness.closed_forms.plane_scene import NotAnalytic, PlaneScene, load_plane_scene
from harness.closed_forms.sphere import check_resting, nearest_hit
from harness.engines.base import Engine, RenderResult
from harness.integrators import entry

#: Pixel samples per draw of random numbers (it fixes the image a seed gives).
CHUNK_PIXELS = 1 << 17
#: Pixel samples traced per pass: arrays small enough to stay in cache, large enough that numpy's per-call cost
#: is small.
BLOCK_PIXELS = 1 << 15
#: A direction's rows in the order y, x, z. BLAS's matrix-vector product (numpy's d @ w over (n, 3) rows) sums
#: d . w fused in the order y, x, z, its matrix product in the order of the rows: one matrix product over rows
#: y, x, z then gives d . w for two vectors w at once, with d @ w's bits.
YXZ = [1, 0, 2]


def load(scene: str, params: dict[str, str] | None = None, integrator: str | None = None) -> PlaneScene | Furnace:
    """The scene, if the engine has its image (with `integrator`'s closed form, if given); else NotAnalytic."""
    try:
        f = load_furnace(scene, params)
    except NotAnalytic:
        pass
    else:
        if integrator is not None:
            form = entry(integrator).analytic
            if form is None or form.furnace is None:
                raise NotAnalytic(f"integrator {integrator} has no closed form in a furnace "
                                  f"({entry(integrator).source})")
            form.furnace(f)  # raises NotAnalytic where it has none for this furnace
        return f
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
    """Closed forms for a lone plane, a sphere resting on it and a furnace; `render` raises NotAnalytic
    otherwise."""

    name = "analytic"

    @staticmethod
    def samples_for(integrator: str, spp: int) -> int:
        """Samples per pixel to render where the tested engine renders `spp`: four times as many where the closed
        form is sampled (its noise then predicts what the tested engine may miss), as many where it is noiseless per
        ray."""
        return 4 * spp if entry(integrator).analytic.sample is not None else spp

    @staticmethod
    def draws_estimator(integrator: str) -> bool:
        """Whether its render of `integrator` draws the tested estimator (the same camera rays, each shaded
        exactly or by the entry's `sample`), so that the tested engine's noise is judged against it; False where
        the closed form knows the image's mean only (direct's)."""
        form = entry(integrator).analytic
        return form is None or form.draws_estimator

    def version(self) -> str:
        return "analytic (closed form, numpy pixel integration)"

    @staticmethod
    def supports(scene: str, params: dict[str, str] | None = None, integrator: str | None = None) -> bool:
        """Whether `scene` is a lone plane, a sphere resting on one or a furnace (and `integrator`, if given, has
        a closed form for that kind of scene)."""
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
        seconds = {"load": time.perf_counter() - start}
        if isinstance(s, Furnace):  # one value everywhere, without noise
            value = np.asarray(form.furnace(s), dtype=float)
            images = np.broadcast_to(value, (batches, s.height, s.width, 3)).astype(np.float32)
            seconds["render"] = time.perf_counter() - start - seconds["load"]
            seconds["total"] = time.perf_counter() - start
            return RenderResult(self.name, str(scene), integrator, spp, seed, images, seconds)
        tracer = _Tracer(s, form)
        pixels = s.width * s.height
        chunk = max(1, CHUNK_PIXELS // pixels)
        block = max(1, BLOCK_PIXELS // pixels)
        # Per sample: x and y jitter, then one u per surface (the sphere's first) where the closed form is sampled.
        per_sample = 2 + (len(tracer.views) if form.sample else 0)
        images = []
        for _ in range(batches):
            acc = np.zeros((3, pixels))
            for first in range(0, spp, chunk):
                count = min(chunk, spp - first)
                u = rng.random((per_sample, count * pixels))
                total = np.zeros((3, pixels))  # the chunk's samples, summed in turn per pixel
                for i in range(0, count, block):
                    value = tracer.trace(u[:, i * pixels : (i + block) * pixels])
                    for sample in range(value.shape[1] // pixels):
                        total += value[:, sample * pixels : (sample + 1) * pixels]
                acc += total
            images.append((acc / spp).T.reshape(s.height, s.width, 3).astype(np.float32))
        seconds["render"] = time.perf_counter() - start - seconds["load"]
        seconds["total"] = time.perf_counter() - start
        return RenderResult(self.name, str(scene), integrator, spp, seed, np.stack(images), seconds)


class _Tracer:
    """Camera rays of one scene, their hits and the closed form there. Arrays are kept as rows of x, y and z
    components (the closed forms get (n, 3) views of them): numpy runs an operation over a last axis of 3 three
    elements at a time."""

    def __init__(self, s: PlaneScene, form) -> None:
        self.s, self.form = s, form
        self.inv_plane = np.linalg.inv(s.plane)
        normal = np.linalg.inv(s.plane[:3, :3]).T @ np.array([0.0, 0.0, 1.0])
        self.normal = normal / np.linalg.norm(normal)
        self.offset = (s.plane[:3, 3] - s.origin) @ self.normal  # t = offset / (d . normal) on the plane
        oc = s.origin - s.sphere.center if s.sphere else self.normal
        self.dots = np.stack([self.normal[YXZ], oc[YXZ]])  # d . normal and d . oc, from d's rows y, x, z
        self.to_world = s.to_world[YXZ]
        self.ys, self.xs = (a.ravel().astype(float) for a in np.mgrid[0 : s.height, 0 : s.width])
        self.views = ([dataclasses.replace(s, surface="sphere", reflectance=s.sphere.reflectance)] if s.sphere
                      else []) + [dataclasses.replace(s, surface="floor") if s.sphere else s]

    def trace(self, u: np.ndarray) -> np.ndarray:
        """The closed form (3, n) at the camera samples that u's rows (x and y jitter, then the closed form's
        u per surface) give, whole numbers of samples per pixel (n); 0 where a ray misses."""
        s, pixels = self.s, self.xs.size
        local = _camera_rays(s, u[0].reshape(-1, pixels), u[1].reshape(-1, pixels), self.xs, self.ys)
        d, lz = self.to_world @ local, local[2]
        denom, b = self.dots @ d
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.divide(self.offset, denom)
            p = np.empty_like(d)
            for k, row in enumerate(YXZ):
                np.multiply(t, d[row], out=p[k])
                p[k] += s.origin[k]
        hit = _on_plane(s, t, lz, denom, self.inv_plane[:2, :3] @ p, self.inv_plane[:2, 3])
        value = np.zeros_like(p)
        draws = u[2:] if self.form.sample else [None, None]  # the sphere's u, then the floor's
        if s.sphere is not None:
            ts = nearest_hit(s, b)
            on_sphere = _clipped(s, ts, lz)
            on_sphere &= ~hit | (ts < t)
            hit &= ~on_sphere
            rows = _rows(on_sphere)
            q = _take(d, rows)[YXZ]
            ts = ts[rows]
            for k in range(3):
                q[k] *= ts
                q[k] += s.origin[k]
            # The normals in C order: BLAS rounds a product over F-ordered rows differently (ao takes n @ up).
            radial = np.stack([(q[k] - s.sphere.center[k]) / s.sphere.radius for k in range(3)], axis=-1)
            self._shade(self.views[0], value, rows, q.T, radial, draws[0])
        rows = _rows(hit)
        self._shade(self.views[-1], value, rows, _take(p, rows).T, self.normal, draws[-1])
        return value

    def _shade(self, view: PlaneScene, value: np.ndarray, rows: np.ndarray | slice, p: np.ndarray,
               normal: np.ndarray, u: np.ndarray | None) -> None:
        """value[:, rows] = the closed form at p (those rows' points), sampled with u[rows] if it is sampled."""
        if isinstance(rows, np.ndarray) and rows.size == 0:
            return
        if self.form.sample is None:
            shaded = self.form.shade(view, p, normal)
        else:
            shaded = self.form.sample(view, p, normal, u[rows, None])
        shaded = np.broadcast_to(shaded, p.shape)
        for k in range(3):
            value[k][rows] = shaded[:, k]


def _camera_rays(s: PlaneScene, rx: np.ndarray, ry: np.ndarray, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Unit camera-space directions (3, n) through the pixels (xs, ys) jittered by rx, ry (count, pixels;
    overwritten). In place: a temporary costs as much as the arithmetic."""
    for r, grid, size in ((rx, xs, s.width), (ry, ys, s.height)):
        r += grid
        r /= size
        r *= 2
        np.subtract(1, r, out=r)
        r *= s.tan_half_x
    ry /= s.width / s.height
    length = rx * rx
    length += ry * ry
    length += 1.0
    np.sqrt(length, out=length)
    local = np.empty((3, rx.size))
    np.divide(rx.ravel(), length.ravel(), out=local[0])
    np.divide(ry.ravel(), length.ravel(), out=local[1])
    np.divide(1.0, length.ravel(), out=local[2])
    return local


def _on_plane(s: PlaneScene, t: np.ndarray, lz: np.ndarray, denom: np.ndarray, uv: np.ndarray,
              uv_offset: np.ndarray) -> np.ndarray:
    """Hits between the clip planes, seen from the front side, inside [-1,1]^2 (rows of uv + uv_offset)."""
    hit = _clipped(s, t, lz)
    hit &= denom < 0
    for c, o in zip(uv, uv_offset):
        c += o
        hit &= np.abs(c, out=c) <= 1
    return hit


def _rows(mask: np.ndarray) -> np.ndarray | slice:
    """The rows where mask holds: all as a slice (no copy), else their indices. A lone row is listed twice:
    numpy hands a one-row matrix product to a dot product that rounds differently, and a closed form may use @."""
    if mask.all():
        return slice(None)
    rows = np.flatnonzero(mask)
    return np.repeat(rows, 2) if rows.size == 1 else rows


def _take(a: np.ndarray, rows: np.ndarray | slice) -> np.ndarray:
    """a[:, rows]: one take for all of a's rows."""
    return a[:, rows] if isinstance(rows, slice) else np.take(a, rows, axis=1)


def _clipped(s: PlaneScene, t: np.ndarray, lz: np.ndarray) -> np.ndarray:
    """Hits whose depth along the camera's axis (t times the ray's camera-space z, lz) lies between near_clip
    and far_clip."""
    with np.errstate(invalid="ignore"):
        depth = t * lz
        return (depth > s.near_clip) & (depth < s.far_clip)


__all__ = ["AnalyticEngine", "NotAnalytic", "load"]
