"""Mitsuba's scene loads and renders in long-lived worker processes (harness/engines/python_child.py), one
per render at a time: a scene that segfaults Mitsuba's loader or hangs it (ignoring SIGTERM) fails its own
case in one line, and the worker is replaced on the next render. A worker keeps Mitsuba imported, its variant
set and its kernels compiled between renders. Each render has a time limit: $MCVAL_MITSUBA_TIMEOUT seconds,
else DEFAULT_TIMEOUT."""
from __future__ import annotations

import threading
from pathlib import Path

from harness.engines.base import RenderFailed, RenderResult
from harness.engines.python_child import ChildFailed, ChildRaised, PythonChild, seconds_from_env

TIMEOUT_ENV = "MCVAL_MITSUBA_TIMEOUT"
#: Seconds one Mitsuba render (load and every batch) may take: generous, the reference budgets of a large
#: film take minutes.
DEFAULT_TIMEOUT = 3600.0
#: Seconds a new worker may take to import Mitsuba and set its variant, apart from its first render's limit.
START_SECONDS = 300.0
_lock = threading.Lock()
_idle: list[PythonChild] = []


def render_timeout() -> float:
    """$MCVAL_MITSUBA_TIMEOUT if set (a positive number of seconds), else DEFAULT_TIMEOUT."""
    return seconds_from_env(TIMEOUT_ENV, DEFAULT_TIMEOUT)


def render_in_worker(engine: tuple, scene: str, *args) -> RenderResult:
    """MitsubaEngine(*engine).render_here(scene, *args) in an idle worker (started if there is none). Raises
    what the render raised (Mitsuba's own errors), or RenderFailed when the worker dies or outlives the time
    limit (the worker is then ended)."""
    result = call_in_worker(engine, f"{__name__}:render", (str(Path(scene).resolve()), *args),
                            f"while loading or rendering {Path(scene).name}")
    result.scene = str(scene)
    return result


def call_in_worker(engine: tuple, function: str, args: tuple, doing: str):
    """`function` ("module:name", run in the worker) on `args` in an idle worker made for MitsubaEngine(*engine)
    (started if there is none), under the render time limit. Raises what the function raised, or RenderFailed
    saying what the worker was `doing` when it died or outlived the limit (the worker is then ended)."""
    timeout = render_timeout()
    with _lock:
        worker = None
        while _idle and worker is None:
            worker = _idle.pop()
            if not worker.alive:
                worker.close()
                worker = None
    kept = False
    try:
        try:
            if worker is None:
                worker = PythonChild()
                worker.call(f"{__name__}:start", engine, timeout=START_SECONDS)
            result = worker.call(function, engine, *args, timeout=timeout)
        except ChildRaised as e:
            kept = _keep(worker)
            raise (e.original or RuntimeError(e.reason)) from None
        except ChildFailed as e:
            raise RenderFailed(f"Mitsuba {e.reason} {doing}", e.output) from None
        kept = _keep(worker)
        return result
    finally:
        if worker is not None and not kept:
            worker.close()  # failed, or interrupted mid-call: its state is unknown


def _keep(worker: PythonChild) -> bool:
    with _lock:
        _idle.append(worker)
    return True


_engines: dict[tuple, object] = {}


def engine(args: tuple):
    """In the worker: MitsubaEngine(*args), made once per distinct arguments (variant, sampler, native, robust)."""
    from harness.engines.mitsuba import MitsubaEngine

    if args not in _engines:
        _engines[args] = MitsubaEngine(*args)
    return _engines[args]


def start(args: tuple) -> None:
    """In a new worker: import Mitsuba and make the engine."""
    engine(args)


def render(args: tuple, *render_args) -> RenderResult:
    """In the worker: MitsubaEngine(*args).render_here(*render_args)."""
    return engine(args).render_here(*render_args)
