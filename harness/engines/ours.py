"""Our renderer, through its Python module `mcrender` (built by CMake, see the Makefile)."""
from __future__ import annotations

import time

import numpy as np

from harness.engines.base import Engine, RenderResult, WarpFunctions


def _load_module():
    try:
        import mcrender
    except ImportError as e:
        raise RuntimeError("the renderer's Python module `mcrender` is not built or not on the path: "
                           "run `make build` (it builds it into build/python)") from e
    return mcrender


class OurEngine(Engine):
    """The C++ renderer under test."""

    name = "mcval"
    render_timing = "render only (scene load and BVH build are timed apart)"

    def __init__(self) -> None:
        self._m = _load_module()

    def version(self) -> str:
        return "mcrender (this repository)"

    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        sample_fn = getattr(self._m, name, None)
        pdf_fn = getattr(self._m, name + "_pdf", None)
        if sample_fn is None or pdf_fn is None:
            return None
        extra = () if alpha is None else (float(alpha),)

        def sample(u: np.ndarray) -> np.ndarray:
            return sample_fn(np.ascontiguousarray(u, dtype=np.float32), *extra).astype(np.float64)

        def pdf(p: np.ndarray) -> np.ndarray:
            return pdf_fn(np.ascontiguousarray(p, dtype=np.float32), *extra).astype(np.float64)

        def native_run(n: int):
            u = np.random.default_rng(1).random((n, 2), dtype=np.float32)
            return lambda: sample_fn(u, *extra)

        return WarpFunctions(sample, pdf, native_run)

    def render(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None) -> RenderResult:
        """Seconds: "load" (parse the scene, read meshes), "build" (BVH), "render" (all batches), "total"."""
        start = time.perf_counter()
        out = self._m.render(str(scene), spp=spp, seed=seed, batches=batches, integrator=integrator,
                             params={k: str(v) for k, v in (params or {}).items()})
        total = time.perf_counter() - start
        stats = out["stats"]
        seconds = {"load": stats["load_seconds"], "build": stats["bvh_seconds"],
                   "render": stats["render_seconds"], "total": total}
        return RenderResult(self.name, str(scene), integrator, spp, seed, np.asarray(out["batches"]), seconds)
