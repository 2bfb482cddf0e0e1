"""Mitsuba 3 as the reference engine (PyPI `mitsuba`, variant llvm_ad_rgb by default)."""
from __future__ import annotations

import glob
import os
import time
from pathlib import Path

import numpy as np

from harness.engines import mitsuba_direct
from harness.engines.base import Engine, RenderResult, WarpFunctions
from harness.engines.mitsuba_integrators import mitsuba_mapping
from harness.engines.mitsuba_scene import load_scene
from harness.engines.mitsuba_worker import render_in_worker
from harness.integrators import entry

DEFAULT_VARIANT = "llvm_ad_rgb"
#: The sampler plugins of Mitsuba 3 an engine can be told to render with.
SAMPLERS = ("independent", "stratified", "multijitter", "orthogonal", "ldsampler")


def _find_llvm() -> str | None:
    """Dr.Jit needs LLVM 19 on Debian 12 (15 and 16 crash): the libllvm19 package's library."""
    for pattern in ("/usr/lib/*/libLLVM.so.19*", "/usr/lib/*/libLLVM-19.so", "/usr/lib/llvm-19/lib/libLLVM*.so*"):
        found = sorted(glob.glob(pattern))
        if found:
            return found[0]
    return None


def load_mitsuba(variant: str = DEFAULT_VARIANT):
    """Import mitsuba with `variant` set; for llvm variants, point Dr.Jit at LLVM 19 first."""
    if variant.startswith("llvm") and not os.environ.get("DRJIT_LIBLLVM_PATH"):
        path = _find_llvm()
        if path is None:
            raise RuntimeError(f"Mitsuba variant {variant} needs LLVM 19: `sudo apt-get install libllvm19` "
                               "or set DRJIT_LIBLLVM_PATH")
        os.environ["DRJIT_LIBLLVM_PATH"] = path
    import mitsuba as mi
    mi.set_variant(variant)
    return mi


#: Scenes whose Mitsuba render is another scene file that must give the same image. far_from_origin is
#: sphere_plane scaled by 1000 and moved 1e5 from the origin: the same image, rendered by Mitsuba where its ray
#: offset ((1 + max|p|) * 9e-5) is not stretched by the distance.
SCENE_SUBSTITUTES = {"far_from_origin": "sphere_plane"}


class MitsubaEngine(Engine):
    """Mitsuba 3 from PyPI. Unless `native`, its `direct` integrator becomes `mcval_direct`, the same with the
    ray offset at its limit (harness/engines/mitsuba_direct.py): Mitsuba's own offset decides pixels where a
    shadow ray grazes a fine mesh, and the reference must not. `native` keeps Mitsuba's integrators, for
    testing Mitsuba itself (its invariances); `robust` sets Mitsuba's embree_use_robust_intersections in every
    scene (speed like for like with a renderer that runs Embree's robust mode, as ours does)."""

    name = "mitsuba"
    samplers = ("independent", "ldsampler", "multijitter")
    best_samplers = ("ldsampler", "multijitter")
    #: Its wavefront holds every sample of a render at once: 768^2 x 512 would not fit in memory.
    pass_spp = 64

    render_timing = ("render only (scene load and BVH build are timed apart); with an llvm variant the first "
                     "render of each sample count also JIT-compiles, so medians of several runs are warm")

    def __init__(self, variant: str = DEFAULT_VARIANT, sampler: str | None = None, native: bool = False,
                 robust: bool = False) -> None:
        if sampler is not None and sampler not in SAMPLERS:
            raise ValueError(f"unknown Mitsuba sampler {sampler!r}: one of {', '.join(SAMPLERS)}")
        self.variant = variant
        self.native = native
        #: Every scene with Mitsuba's `embree_use_robust_intersections` set: Embree's robust triangle test, as
        #: ours runs, for a like-for-like speed comparison (Mitsuba's default is the faster, non-robust one).
        self.robust = robust
        self.name = f"mitsuba-{variant.split('_')[0]}" if variant != DEFAULT_VARIANT else (
            "mitsuba-robust" if robust else "mitsuba-native" if native else "mitsuba")
        if variant != DEFAULT_VARIANT:
            self.samplers, self.best_samplers = ("independent",), ()
        self.sampler = sampler  # None: the scene's (mapped); else a Mitsuba sampler plugin name
        self.label = self.name if sampler is None else f"{self.name}/{sampler}"
        self._exact: dict[tuple[str, int], bool] = {}
        self._mi = load_mitsuba(variant)
        import drjit
        self._dr = drjit

    def scene_file(self, path: Path) -> Path:
        substitute = path.with_name(f"{SCENE_SUBSTITUTES.get(path.stem, path.stem)}.xml")
        # Only for the suite's own scenes (in its scenes/ folder, or a worker's copy of it), never a user's.
        return substitute if path.parent.name == "scenes" and substitute.exists() else path

    def integrator_mapping(self, integrator: str) -> str | None:
        """Its plugin and properties for `integrator`, then what its copy of a scene drops or adds, "; "-separated
        (harness/engines/mitsuba_integrators.py)."""
        return mitsuba_mapping(integrator).summary()

    def draws_same_estimator(self, scene: Path, integrator: str) -> bool:
        return mitsuba_mapping(integrator).draws_same_estimator(scene)

    def reads_integrator_parameters(self, integrator: str) -> bool:
        """Its plugin of the integrator's name takes the file's values of the entry's parameters
        (MitsubaMapping.file_values); a plugin of another name is given set values."""
        names = {name for _, name, _ in entry(integrator).parameters}
        return bool(names) and names <= set(mitsuba_mapping(integrator).file_values)

    def _arguments(self) -> tuple:
        """What makes this engine again in another process: MitsubaEngine(*arguments)."""
        return self.variant, self.sampler, self.native, self.robust

    def __reduce__(self):
        # To a worker as its arguments: each worker process loads Mitsuba, sets the variant and JIT-compiles
        # its own kernels (both are per process), and finds LLVM itself (load_mitsuba).
        return MitsubaEngine, self._arguments()

    def renders_exactly(self, spp: int) -> bool:
        """Whether the sampler keeps `spp` as asked. Several round it: ldsampler up to a power of 4,
        multijitter to a near-square grid (32 -> 35), stratified and orthogonal to squares. Asked of the
        plugin itself, so a new sampler or a new Mitsuba needs no table here."""
        if self.sampler is None:
            return True
        if (self.sampler, spp) not in self._exact:
            mi = self._activate()
            logger = mi.logger()
            level = logger.log_level()
            logger.set_log_level(mi.LogLevel.Error)  # rounding is what is asked here, not worth a warning
            try:
                probe = mi.load_dict({"type": self.sampler})
                probe.set_sample_count(spp)
            finally:
                logger.set_log_level(level)
            self._exact[(self.sampler, spp)] = probe.sample_count() == spp
        return self._exact[(self.sampler, spp)]

    def version(self) -> str:
        tight = "" if self.native else f", {mitsuba_direct.PLUGIN} for direct"
        robust = ", Embree's robust intersections" if self.robust else ""
        return f"mitsuba {self._mi.__version__} ({self.variant}), drjit {self._dr.__version__}{tight}{robust}"

    def _activate(self):
        """Mitsuba's variant is process-wide: make sure this engine's is the one in force."""
        if self._mi.variant() != self.variant:
            self._mi.set_variant(self.variant)
        return self._mi

    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        # In this process, unlike renders: Mitsuba's warps are its own tested code on arrays the harness
        # makes, not a user's scene, and a worker would add a copy of each million samples to every call.
        mi, dr = self._activate(), self._dr
        if not self.variant.startswith("llvm"):
            return None  # scalar variants take one sample per call: no array warps
        sample_fn = getattr(mi.warp, name, None)
        pdf_fn = getattr(mi.warp, name + "_pdf", None)
        if sample_fn is None or pdf_fn is None:
            return None
        extra = () if alpha is None else (float(alpha),)

        def sample(u: np.ndarray) -> np.ndarray:
            self._activate()
            if not len(u):  # Dr.Jit refuses arrays of size 0 (operands of incompatible sizes): one, then none
                return sample(np.full((1, 2), 0.5))[:0]
            out = sample_fn(mi.Point2f(np.asarray(u, np.float32).T), *extra)
            return np.array(out, dtype=np.float64).T

        def pdf(p: np.ndarray) -> np.ndarray:
            self._activate()
            if not len(p):
                return np.zeros(0)
            p = np.asarray(p, np.float32).T
            arg = mi.Point2f(p) if p.shape[0] == 2 else mi.Vector3f(p)
            values = np.array(pdf_fn(arg, *extra), dtype=np.float64).reshape(-1)
            # Constant densities come back as a single value.
            return np.broadcast_to(values, (p.shape[1],)).copy()

        def native_run(n: int):
            self._activate()
            u = mi.Point2f(np.random.default_rng(1).random((2, n), dtype=np.float32))
            dr.eval(u)

            def run():
                dr.eval(sample_fn(u, *extra))
                dr.sync_thread()
            return run

        return WarpFunctions(sample, pdf, native_run)

    def render(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None) -> RenderResult:
        """Seconds: "load" (parse, build the scene and its BVH), "first" (the first batch, with the
        JIT compilation of an llvm variant), "render" (all batches), "total". In a worker process
        (harness/engines/mitsuba_worker.py): a scene that crashes or hangs Mitsuba raises RenderFailed."""
        return render_in_worker(self._arguments(), scene, integrator, spp, batches, seed, params)

    def render_here(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
                    params: dict[str, str] | None = None) -> RenderResult:
        """`render` in this process (a worker's)."""
        mi = self._activate()
        start = time.perf_counter()
        loaded = load_scene(scene, integrator, sampler=self.sampler, tight=not self.native, robust=self.robust,
                            **(params or {}))
        seconds = {"load": time.perf_counter() - start}
        sampler = loaded.sensors()[0].sampler().class_name()  # e.g. IndependentSampler
        if self.sampler is not None and sampler != mi.load_dict({"type": self.sampler}).class_name():
            # A scene without a <sampler> gets Mitsuba's default: the curve would carry the wrong name.
            raise RuntimeError(f"{scene}: Mitsuba rendered with its {sampler}, not {self.sampler}: the scene's "
                               "sensor declares no <sampler> to replace")
        images = []
        render_start = time.perf_counter()
        for k in range(batches):
            batch_start = time.perf_counter()
            image = np.array(mi.render(loaded, spp=spp, seed=mitsuba_seed(seed, k)), dtype=np.float32)
            images.append(image[..., :3])
            if k == 0:
                seconds["first"] = time.perf_counter() - batch_start
        seconds["render"] = time.perf_counter() - render_start
        seconds["total"] = time.perf_counter() - start
        return RenderResult(self.name, str(scene), integrator, spp, seed, np.stack(images), seconds, sampler)


def mitsuba_seed(seed: int, batch: int) -> int:
    """A distinct 32-bit Mitsuba seed per (seed, batch)."""
    return (seed * 1_000_003 + batch * 7919 + 1) % 2**32
