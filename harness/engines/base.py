"""The one interface through which the harness reaches every engine."""
from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Callable

import numpy as np


@dataclass(frozen=True)
class BsdfFunctions:
    """One BSDF at fixed parameter values, over numpy arrays (float64).

    eval(wi, wo) -> (N,) f(wi, wo) |cos theta_o|;  pdf(wi, wo) -> (N,) density of wo by solid angle;
    sample(wi, u) -> wo (N, 3), weight (N,), pdf (N,), with u (N, 3) uniforms.
    """

    name: str
    params: dict[str, float]
    eval: Callable[[np.ndarray, np.ndarray], np.ndarray]
    pdf: Callable[[np.ndarray, np.ndarray], np.ndarray]
    sample: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]

    @property
    def label(self) -> str:
        """"roughconductor alpha=0.1": the BSDF and its parameter values."""
        return " ".join([self.name, *(f"{k}={v:g}" for k, v in self.params.items())])


@dataclass
class WarpFunctions:
    """An engine's sampler and pdf for one distribution, over numpy arrays.

    sample: (N, 2) uniforms in [0,1)^2 -> (N, 2) or (N, 3) points (float64).
    pdf: points -> (N,) densities (float64).
    native_run: given N, prepares N uniforms in the engine's own containers and
    returns a call that warps them all (for throughput, without conversions).
    """

    sample: Callable[[np.ndarray], np.ndarray]
    pdf: Callable[[np.ndarray], np.ndarray]
    native_run: Callable[[int], Callable[[], Any]]


@dataclass
class RenderResult:
    """K independent renders of one scene by one engine, and what they cost.

    batches: (K, H, W, 3) float32, linear RGB, each batch with `spp` samples per pixel (None once dropped).
    seconds: wall-clock times by phase ("load", "build" or "jit", "render", "total"); what each
    includes is the engine's to say in its docstring.
    """

    engine: str
    scene: str
    integrator: str
    spp: int
    seed: int
    batches: np.ndarray | None
    seconds: dict[str, float]
    #: The sampler the engine rendered with (its plugin name), "" where that does not apply.
    sampler: str = ""
    #: What is kept of dropped batches (see `light`): their mean image, per-batch image means, count.
    kept: tuple[np.ndarray, np.ndarray, int] | None = field(default=None, repr=False)
    #: The rays it traced (camera, shadow and occlusion rays), where the engine counts them; else None.
    rays: int | None = None

    @property
    def mean(self) -> np.ndarray:
        return self.kept[0] if self.batches is None else self.batches.mean(axis=0)

    @property
    def batch_means(self) -> np.ndarray:
        """(K, 3) float64: each batch's image mean (summed in float64: float32 sums round by layout)."""
        return self.kept[1] if self.batches is None else self.batches.mean(axis=(1, 2), dtype=np.float64)

    @property
    def count(self) -> int:
        return self.kept[2] if self.batches is None else len(self.batches)

    def light(self) -> "RenderResult":
        """This result without its batches, keeping what reports read of them: a worker's answer for a
        case that passed travels back at 1/K of the size."""
        if self.batches is None:
            return self
        return replace(self, batches=None, kept=(self.mean, self.batch_means, self.count))


class RenderFailed(RuntimeError):
    """A render that gave no usable image: the engine crashed, was killed, hung or reported an error.

    `reason` is one line for reports, e.g. "killed by signal SIGSEGV (11)", "timed out after 600 s",
    "exited with status 1: <last line of its error output>", "wrote no image". `output` holds the last
    lines (up to 50) of what it printed, where there is any.
    """

    def __init__(self, reason: str, output: str = "") -> None:
        super().__init__(reason)
        self.reason = reason
        self.output = output

    def __reduce__(self):
        return RenderFailed, (self.reason, self.output)


class Engine(ABC):
    """A renderer the harness can drive."""

    #: Short name used in reports and results.json.
    name: str
    #: The name with the sampler it was told to use, if any ("mcval/sobol"): a benchmark's curve label.
    label: str = ""
    #: The samplers `bench` runs it with: the independent one (the like-for-like comparison) first, then its
    #: stratified ones; and those its best curve is chosen from (none: its best curve of any sampler).
    samplers: tuple[str, ...] = ("independent",)
    best_samplers: tuple[str, ...] = ()
    #: Most samples per pixel one render call should take at high resolution (a wavefront engine holds every
    #: sample of a call in memory); None: any number.
    pass_spp: int | None = None
    #: Whether it has warps at all (an engine file's renderer has none: give --warp-library for its warps).
    has_warps: bool = True
    #: Whether its warps' throughput must clear the floor (mcval's), or is only reported (a user's code).
    throughput_judged: bool = True
    #: Whether a warp it lacks is left out of the matrix (a user's library) rather than failed (mcval's).
    warps_optional: bool = False
    #: The integrators (mcval's names) it renders; None: every integrator the harness has an entry for.
    integrators: tuple[str, ...] | None = None
    #: Whether its renders run in another process: then the harness prepares and compares beside a render (an
    #: in-process render would compete with it for the interpreter).
    renders_elsewhere: bool = False

    def scene_file(self, path: Path) -> Path:
        """The scene file this engine renders for `path`: the same file, unless the engine needs another one
        that gives the same image (see MitsubaEngine)."""
        return path

    def integrator_mapping(self, integrator: str) -> str | None:
        """How it renders mcval's `integrator` (an entry of harness/integrators/), in one line for listings:
        its own name for it, or the plugin and what its copy of a scene drops (Mitsuba); None where it does
        not render it. Derived from the entry's engine-neutral facts, so a new integrator needs no edit here."""
        return integrator if self.integrators is None or integrator in self.integrators else None

    def draws_same_estimator(self, scene: Path, integrator: str) -> bool:
        """Whether its render of `scene` with `integrator` draws the integrator's own estimator, sample for
        sample (the same camera rays and the same shading estimate of each). Then a tested engine whose batches
        are all alike where this engine's vary ignores its seed, and the two engines' variances must agree
        (harness.comparison.independence_check, variance_check). False unless the engine knows it does."""
        return False

    def draws_integrator_estimator(self, integrator: str) -> bool:
        """Whether, as the engine under test, it draws `integrator`'s own estimator (the one its entry defines, as
        Mitsuba's plugin does): then a reference engine that draws it too judges its noise as well as its mean.
        True unless the engine says it draws another estimator of the same image (an engine file's
        `other_estimators`): a different, unbiased estimator has other noise, which is no defect."""
        return True

    def reads_integrator_parameters(self, integrator: str) -> bool:
        """Whether it renders `integrator` with the values that a scene file's own <integrator> of that type gives
        every one of its parameters (the entry's `parameters`: direct's emitter_samples and bsdf_samples, path's
        strategy too). Then a suite asks
        for one of the integrator's settings (its strategies: harness/images/strategy_renders.py) by writing
        it into a copy of the scene. False unless the engine knows it does."""
        return False

    def renders_exactly(self, spp: int) -> bool:
        """Whether a render asked for `spp` samples per pixel takes exactly that many (a sampler may round)."""
        return True

    def render(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None) -> RenderResult:
        """Render `scene` with our integrator `integrator` (an entry of harness/integrators/), `batches`
        independent times at `spp` samples per pixel; `params` override the scene's <default>s.
        Raises RenderFailed when the engine crashes, hangs or fails to produce the image."""
        raise NotImplementedError(f"engine {self.name} does not render images")

    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        """The warp called `name` (Mitsuba's snake-case name, e.g. "square_to_tent"),
        with its parameter if it has one; None if this engine lacks that distribution."""
        return None

    @abstractmethod
    def version(self) -> str:
        """What exactly is running (library version, variant), for provenance."""

    def describe(self) -> dict[str, str]:
        """Provenance for reports, JSON and JUnit: its name and version (and, for an engine file, its file and
        command)."""
        return {"name": self.name, "version": self.version()}
