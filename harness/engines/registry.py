"""The only code that maps an engine's name to the engine: the engines of this package, plus every *.py file
with an `ENGINE` (an EngineEntry) in the folders of $MCVAL_ENGINE_PATH (os.pathsep-separated), so an engine
is one file and one registry line, and a test can add one without editing the harness.

The suites never name an engine: the commands make a *test* engine and a *reference* engine from the names
they are given (`--engine`, `--reference`) and hand both over.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field, replace
from functools import cache
from typing import Any, Callable

from harness.engines.base import Engine
from harness.engines.engine_file import looks_like_engine_file, read_engine_file
from harness.plugin_files import plugin_objects

PATH_ENV = "MCVAL_ENGINE_PATH"
#: The engines the commands use unless told otherwise.
DEFAULT_TEST = "mcval"
DEFAULT_REFERENCE = "mitsuba"


@dataclass(frozen=True)
class EngineEntry:
    """One engine as the commands see it: its name and how to make it from the options a command has
    (`variant`: a Mitsuba variant; `sampler`: a sampler to use instead of the scene's; `in_process`: render
    in this process, for timing)."""

    name: str
    make: Callable[[dict[str, Any]], Engine]
    summary: str
    source: str = field(default="", compare=False)  # the file it was read from


def _mcval(options: dict[str, Any]) -> Engine:
    from harness.engines.mcval import McvalEngine
    return McvalEngine(sampler=options.get("sampler"), in_process=options.get("in_process", False))


def _mitsuba(variant: str | None, native: bool = False, robust: bool = False) -> Callable[[dict[str, Any]], Engine]:
    def make(options: dict[str, Any]) -> Engine:
        from harness.engines.mitsuba import DEFAULT_VARIANT, MitsubaEngine
        return MitsubaEngine(variant or options.get("variant") or DEFAULT_VARIANT, sampler=options.get("sampler"),
                             native=native, robust=robust)
    return make


def _analytic(options: dict[str, Any]) -> Engine:
    from harness.engines.analytic import AnalyticEngine
    return AnalyticEngine()


BUILT_IN = (
    EngineEntry("mcval", _mcval, "this repository's renderer (`render` as a child process, warps in process)"),
    EngineEntry("mitsuba", _mitsuba(None), "Mitsuba 3 from PyPI (--variant, default llvm_ad_rgb); its direct "
                "integrator with the ray offset at its limit (mcval_direct)"),
    EngineEntry("mitsuba-native", _mitsuba(None, native=True), "Mitsuba 3 with its own integrators and ray "
                "offset, as shipped (--variant)"),
    EngineEntry("mitsuba-robust", _mitsuba(None, native=True, robust=True), "Mitsuba 3 as shipped but for Embree's "
                "robust intersections (embree_use_robust_intersections), as this repository's renderer runs Embree: "
                "speed like for like"),
    EngineEntry("mitsuba-scalar", _mitsuba("scalar_rgb", native=True), "Mitsuba 3, scalar_rgb, as shipped"),
    EngineEntry("analytic", _analytic, "the integrators' closed forms on the analytic scenes"),
)


def _path_entries(folders: str) -> list[EngineEntry]:
    found = []
    for path, entry in plugin_objects(folders, "ENGINE", PATH_ENV):
        if not isinstance(entry, EngineEntry):
            raise ValueError(f"{path}: ENGINE is a {type(entry).__name__}, expected an EngineEntry "
                             "(harness.engines.registry)")
        found.append(replace(entry, source=str(path)))
    return found


@cache
def _entries(folders: str) -> dict[str, EngineEntry]:
    out: dict[str, EngineEntry] = {}
    for entry in (*BUILT_IN, *_path_entries(folders)):
        if entry.name in out:
            raise ValueError(f"{entry.source or 'harness/engines/registry.py'}: engine {entry.name!r} is "
                             f"already registered")
        out[entry.name] = entry
    return out


def engine_entries() -> dict[str, EngineEntry]:
    """Every engine, by name: the built-in ones, then those of $MCVAL_ENGINE_PATH."""
    return _entries(os.environ.get(PATH_ENV, ""))


def make_engine(name: str, **options: Any) -> Engine:
    """The engine called `name`, made with `options`, or the engine an engine file describes (a path ending in
    .toml, docs/engines.md); ValueError naming the known engines if there is none."""
    if looks_like_engine_file(name):
        from harness.engines.command import CommandEngine
        return CommandEngine.from_path(name, options.get("sampler"))
    found = engine_entries()
    if name not in found:
        raise ValueError(f"unknown engine {name!r}: known are {', '.join(found)}")
    return found[name].make(options)


def engine_integrators(name: str) -> tuple[str, ...] | None:
    """The integrators the engine `name` renders (Engine.integrators; an engine file's table is read without
    making its engine); None: every integrator with an entry."""
    if looks_like_engine_file(name):
        return tuple(read_engine_file(name).integrators)
    return make_engine(name).integrators


def scene_bounds(text: str) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """(min, max) of the scene `text` as Mitsuba 3 loads it, in a worker process (harness/engines/mitsuba_bounds.py):
    where the image suite places the camera of a --scene file without a sensor. None for a scene without shapes."""
    from harness.engines.mitsuba_bounds import scene_bounds as mitsuba_bounds
    return mitsuba_bounds(text)
