"""Our renderer: images through the `render` CLI in a child process (see render_process), warps through
its Python module `mcval_renderer` (both built by CMake, see the Makefile)."""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from harness.engines.base import Engine, RenderResult, WarpFunctions
from harness.engines.render_process import render_binary, run_render
from harness.native import renderer_module


class McvalEngine(Engine):
    """This repository's C++ renderer, the engine named mcval.

    binary: the `render` CLI (default: $MCVAL_RENDER, else build/render); timeout: seconds per render
    (default: $MCVAL_RENDER_TIMEOUT, else 600 s plus a share per sample, see render_process).
    """

    name = "mcval"
    samplers = ("independent", "sobol")
    best_samplers = ("sobol",)
    render_timing = "render only (scene load and BVH build are timed apart)"

    def __init__(self, binary: str | Path | None = None, timeout: float | None = None,
                 sampler: str | None = None, in_process: bool = False) -> None:
        self._m = renderer_module()
        self.binary = binary
        self.timeout = timeout
        self.sampler = sampler  # None: the scene's; else "independent" or "sobol" (render --sampler)
        self.label = self.name if sampler is None else f"{self.name}/{sampler}"
        # In process (the bench): renders through the Python module, as Mitsuba's do, so that both engines
        # time warm thread pools; a crash then ends the process, which the child process would contain.
        self.in_process = in_process
        self.renders_elsewhere = not in_process

    @property
    def integrators(self) -> tuple[str, ...]:
        """The integrators of the renderer's registry, in its order (mcval_renderer.integrators())."""
        if not hasattr(self._m, "integrators"):
            raise RuntimeError(f"{self._m.__file__} has no integrators(): it was built before the renderer's "
                               "integrator registry; run `make build`")
        return tuple(self._m.integrators())

    def reads_integrator_parameters(self, integrator: str) -> bool:
        """The loader reads the file's <integrator> where its type is the integrator asked for."""
        return integrator in self.integrators

    def __reduce__(self):
        # To a worker as its arguments: the module and the default binary are the worker's own.
        return McvalEngine, (self.binary, self.timeout, self.sampler, self.in_process)

    def version(self) -> str:
        return f"this repository's renderer (images: {self.binary or render_binary()} as a child process; " \
               "warps: the mcval_renderer module)"

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
        """Seconds: "load" (parse the scene, read meshes), "build" (BVH), "render" (all batches), as timed
        inside the renderer; "total" (wall clock, with process start and EXR write and read).
        Raises RenderFailed if the child crashes, is killed, times out, exits non-zero or writes no image."""
        start = time.perf_counter()
        if self.in_process:
            return self._render_in_process(scene, integrator, spp, batches, seed, params, start)
        out = run_render(str(scene), integrator, spp, batches, seed, {k: str(v) for k, v in (params or {}).items()},
                         self.timeout, self.binary, self.sampler)
        seconds = {**out.seconds, "total": time.perf_counter() - start}
        return RenderResult(self.name, str(scene), integrator, spp, seed, out.batches, seconds, out.sampler)

    def _render_in_process(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
                           params: dict[str, str] | None, start: float) -> RenderResult:
        kwargs = {"sampler": self.sampler} if self.sampler else {}
        out = self._m.render(str(scene), spp=spp, batches=batches, seed=seed, integrator=integrator,
                             params={k: str(v) for k, v in (params or {}).items()}, **kwargs)
        s = out["stats"]
        seconds = {"load": s["load_seconds"], "build": s["bvh_seconds"], "render": s["render_seconds"],
                   "total": time.perf_counter() - start}
        return RenderResult(self.name, str(scene), integrator, spp, seed, np.asarray(out["batches"]), seconds,
                            s["sampler"], rays=s["camera_rays"] + s["shadow_rays"])
