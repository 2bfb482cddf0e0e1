"""Renders of a serial image run started ahead of the case that needs them.

A render of ours runs in another process (the render worker) and leaves this one idle; the references, the
closed forms and the comparisons of a case run here and leave the worker idle. Our render of case k + 1
starts while case k is compared, and the closed forms (numpy, which lets go of the interpreter over whole
arrays) are computed on a thread of their own from the start. Only for a serial run of an engine that renders
elsewhere: on Dask each task renders its own case.
"""
from __future__ import annotations

from concurrent.futures import Future

from harness.engines.base import Engine
from harness.engines.render_thread import RenderThread
from harness.images.suite import ImageCase
from harness.statistics.constants import IMAGE_BATCHES


def render_args(case: ImageCase, seed: int, params: dict[str, str]) -> tuple:
    """The arguments of the tested engine's render of `case` (Engine.render), wherever it is started."""
    return str(case.path), case.integrator, case.test_spp, IMAGE_BATCHES, seed, params


def closed_form_args(case: ImageCase, seed: int, params: dict[str, str]) -> tuple:
    """The arguments of the analytic engine's render of `case`: its own samples and seed beside ours."""
    from harness.engines.analytic import AnalyticEngine

    spp = AnalyticEngine.samples_for(case.integrator, case.test_spp)
    return str(case.path), case.integrator, spp, IMAGE_BATCHES, seed + 1, params


class RenderAhead:
    """The renders of a run's cases by `engine`, in order, on one thread. `args[k]`: the Engine.render
    arguments of case k, None where it has no render; asking for case k's starts the next `depth` ones
    (None: every render starts at once)."""

    def __init__(self, engine: Engine, args: list[tuple | None], depth: int | None = 1) -> None:
        self._engine, self._args = engine, args
        self._thread = RenderThread()
        self._started: dict[int, Future] = {}
        self._depth = len(args) if depth is None else depth
        if depth is None:
            self._start(range(len(args)))

    def _start(self, indices) -> None:
        for j in indices:
            if j < len(self._args) and self._args[j] is not None and j not in self._started:
                self._started[j] = self._thread.submit(self._engine.render, *self._args[j])

    def render(self, k: int) -> Future:
        """Case k's render (started now if it was not), after starting the next ones."""
        self._start(range(k, k + 1 + self._depth))
        return self._started.pop(k)

    def close(self) -> None:
        """End a render nobody asked for (the run stopped early, or was interrupted)."""
        self._thread.close()
