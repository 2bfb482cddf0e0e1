"""Our renders of a serial image run, each started while the case before it is compared.

A render of ours runs in another process (the render worker) and leaves this one idle; the references, the
closed forms and the comparisons of a case run here and leave the worker idle. Rendering case k + 1 while case
k is compared overlaps the two. Only for a serial run of an engine that renders elsewhere: on Dask each task
renders its own case.
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


class RenderAhead:
    """The renders of `cases` by `engine`, in order, on one thread: asking for case k's starts case k + 1's.
    `args[k]`: render_args of case k."""

    def __init__(self, engine: Engine, args: list[tuple]) -> None:
        self._engine, self._args = engine, args
        self._thread = RenderThread()
        self._started: dict[int, Future] = {}

    def render(self, k: int) -> Future:
        """Case k's render (started now if it was not), after starting case k + 1's."""
        for j in (k, k + 1):
            if j < len(self._args) and j not in self._started:
                self._started[j] = self._thread.submit(self._engine.render, *self._args[j])
        return self._started.pop(k)

    def close(self) -> None:
        """End a render nobody asked for (the run stopped early, or was interrupted)."""
        self._thread.close()
