"""The warp conformance matrix: every warp of our renderer, Beckmann at several alphas, against its own pdf, the
closed form of its name and Mitsuba."""
from __future__ import annotations

import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from harness.engines.base import Engine
from harness.engines.python_child import ChildFailed
from harness.statistics.constants import SIGNIFICANCE, WARP_SAMPLES
from harness.warps.power import CACHE_PATH as POWER_CACHE
from harness.warps.power import attach_power
from harness.warps.evaluate import WarpResult, decide, evaluate_warp, failed_warp
from harness.warps.targets import target_for
from harness.warps.throughput import throughput_check

#: Beckmann roughnesses in the matrix; small ones are where careless cell integrals fail.
BECKMANN_ALPHAS = (0.01, 0.05, 0.1, 0.3, 1.0)
#: Roughnesses swept by the hard-inputs check of every Beckmann entry.
HARD_ALPHAS = tuple(float(a) for a in np.logspace(-4, 1, 11))


@dataclass(frozen=True)
class WarpSpec:
    """One row of the matrix: a warp (Mitsuba's name), its domain, its parameter."""

    name: str
    domain: str
    alpha: float | None = None

    @property
    def key(self) -> str:
        """Short id used on the command line (--only) and in file names."""
        short = self.name.removeprefix("square_to_")
        return short if self.alpha is None else f"{short}:{self.alpha:g}"

    @property
    def params(self) -> dict | None:
        return None if self.alpha is None else {"alpha": self.alpha}


SUITE: tuple[WarpSpec, ...] = (
    WarpSpec("square_to_uniform_square", "square"),
    WarpSpec("square_to_tent", "tent"),
    WarpSpec("square_to_uniform_disk", "disk"),
    WarpSpec("square_to_uniform_sphere", "sphere"),
    WarpSpec("square_to_uniform_hemisphere", "hemisphere"),
    WarpSpec("square_to_cosine_hemisphere", "hemisphere"),
    *(WarpSpec("square_to_beckmann", "hemisphere", a) for a in BECKMANN_ALPHAS),
)


def select(only: list[str] | None) -> list[WarpSpec]:
    """The specs whose key, or warp name, is in `only` (all of them when `only` is empty)."""
    if not only:
        return list(SUITE)
    chosen = [s for s in SUITE if s.key in only or s.name.removeprefix("square_to_") in only]
    unknown = set(only) - {s.key for s in chosen} - {s.name.removeprefix("square_to_") for s in chosen}
    if unknown:
        raise ValueError(f"unknown warp {', '.join(sorted(unknown))}: choose from {', '.join(s.key for s in SUITE)}")
    return chosen


def spec_seed(spec: WarpSpec, seed: int) -> int:
    """The seed of one warp in a run at `seed`: each warp draws its own uniforms, so warps whose samples
    fill their cells alike (every correct warp, in equal-probability cells) give independent p-values."""
    return int(np.random.SeedSequence([zlib.crc32(spec.key.encode()), seed]).generate_state(1, np.uint64)[0] >> 1)


def check_spec(spec: WarpSpec, tested: Engine, reference: Engine | None, seed: int, samples: int,
               timed: bool = True) -> WarpResult:
    """Every check of one spec: our warp against its pdf and against the reference engine's. A warp in a
    process of its own (a user's library) that crashes, exits or hangs fails alone, with that one line.
    `timed` False skips the throughput (see evaluate_warp)."""
    try:
        return _check_spec(spec, tested, reference, seed, samples, timed)
    except ChildFailed as e:
        return failed_warp(spec.name, spec.params, spec.domain, spec_seed(spec, seed), e.reason)


def _check_spec(spec: WarpSpec, tested: Engine, reference: Engine | None, seed: int, samples: int,
                timed: bool) -> WarpResult:
    functions = tested.warp(spec.name, spec.alpha)
    if functions is None:
        raise RuntimeError(f"engine {tested.name} has no warp {spec.name}")
    ref = reference.warp(spec.name, spec.alpha) if reference is not None else None
    variants = None
    if spec.alpha is not None:
        variants = {}
        for a in HARD_ALPHAS:
            f = tested.warp(spec.name, a)
            variants[f"alpha={a:.3g}"] = (f.sample, f.pdf)
    return evaluate_warp(functions.sample, functions.pdf, spec.domain, name=spec.name, params=spec.params,
                         seed=spec_seed(spec, seed), samples=samples, reference=ref,
                         target=target_for(spec.name, spec.alpha), native_run=functions.native_run,
                         hard_variants=variants, judge_throughput=tested.throughput_judged, timed=timed)


def run_matrix(tested: Engine, reference: Engine | None, specs: list[WarpSpec], seed: int = 0,
               samples: int = WARP_SAMPLES,
               on_progress: Callable[[WarpSpec], None] | None = None,
               power_cache: Path | None = POWER_CACHE, timed: bool = True) -> tuple[list[WarpResult], float]:
    """Check every spec; decide all statistical tests together (Sidak). Returns results and the per-test level.
    `timed` False skips every warp's throughput (see evaluate_warp).

    Each check then gets its power at that level (details["power"], see warp_power), cached in `power_cache`
    (default results/.cache/warp_power.json; None: no cache).
    """
    results = []
    for spec in specs:
        results.append(check_spec(spec, tested, reference, seed, samples, timed))
        if on_progress:
            on_progress(spec)
    level = decide(results, SIGNIFICANCE)
    attach_power(results, [s.key for s in specs], samples, level, power_cache)
    return results, level



def time_matrix(tested: Engine, reference: Engine | None, specs: list[WarpSpec], results: list[WarpResult],
                seed: int, on_progress: Callable[[WarpSpec], None] | None = None) -> list[WarpResult]:
    """The results of a matrix checked with `timed` False, each with its warp's throughput timed now (apart
    from other work: harness/commands/warp_section.py). A warp whose process dies here fails, as in check_spec."""
    timed = []
    for spec, result in zip(specs, results):
        if result.failure is None:
            try:
                functions = tested.warp(spec.name, spec.alpha)
                ref = reference.warp(spec.name, spec.alpha) if reference is not None else None
                result.checks["throughput"] = throughput_check(functions.sample, functions.native_run, ref,
                                                               judged=tested.throughput_judged)
            except ChildFailed as e:
                result = failed_warp(spec.name, spec.params, spec.domain, spec_seed(spec, seed), e.reason)
        timed.append(result)
        if on_progress:
            on_progress(spec)
    return timed
