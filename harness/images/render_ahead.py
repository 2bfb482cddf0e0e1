"""Renders of a serial image run started ahead of the case that needs them.

A render of the tested engine runs in another process (the render worker) and leaves this one idle; the
references, the closed forms and the comparisons of a case run here and leave the worker idle. The tested
render of case k + 1 starts while case k is compared, and the closed forms (numpy, which lets go of the
interpreter over whole arrays) are computed on a thread of their own from the start. Only for a serial run of an
engine that renders elsewhere: on Dask each task renders its own case. `RendersAhead` is a CaseRenders: the
case asks for its renders as it would anyway.
"""
from __future__ import annotations

from collections.abc import Sequence
from concurrent.futures import Future

from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine, RenderResult
from harness.engines.render_thread import RenderThread
from harness.images.case_renders import CaseRenders, closed_form_args, render_args
from harness.images.references import render_params
from harness.images.suite import ImageCase


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

    def has(self, k: int) -> bool:
        """Whether case k has a render here."""
        return 0 <= k < len(self._args) and self._args[k] is not None

    def render(self, k: int) -> Future:
        """Case k's render (started now if it was not), after starting the next ones."""
        self._start(range(k, k + 1 + self._depth))
        return self._started.pop(k)

    def close(self) -> None:
        """End a render nobody asked for (the run stopped early, or was interrupted)."""
        self._thread.close()


class RendersAhead(CaseRenders):
    """CaseRenders for a serial run of `cases` (each at its seed of `seeds`): the tested render of the next case
    starts when a case asks for its own, and the closed forms of the cases that have one (`closed_form`) all
    start at once. A render asked for otherwise (another case or seed) is made when asked, as CaseRenders
    makes it."""

    def __init__(self, tested: Engine, reference: Engine, cases: Sequence[ImageCase], seeds: Sequence[int],
                 closed_form: Sequence[bool]) -> None:
        super().__init__(tested, reference)
        self._index = {(c.key, s): k for k, (c, s) in enumerate(zip(cases, seeds, strict=True))}
        self._tested = RenderAhead(tested, [render_args(c, s, render_params(c)) for c, s in zip(cases, seeds)])
        self._closed = RenderAhead(AnalyticEngine(), [closed_form_args(c, s, render_params(c)) if exact else None
                                                      for c, s, exact in zip(cases, seeds, closed_form)], depth=None)
        self._asked: set[tuple[str, int, str]] = set()

    def _ahead(self, queue: RenderAhead, what: str, case: ImageCase, seed: int) -> Future | None:
        """The render of `case` that `queue` started (or starts now), once; None where it has none."""
        k = self._index.get((case.key, seed))
        if k is None or (case.key, seed, what) in self._asked or not queue.has(k):
            return None
        self._asked.add((case.key, seed, what))
        return queue.render(k)

    def tested(self, case: ImageCase, seed: int) -> RenderResult:
        started = self._ahead(self._tested, "tested", case, seed)
        return started.result() if started is not None else super().tested(case, seed)

    def closed_form(self, case: ImageCase, seed: int) -> RenderResult:
        started = self._ahead(self._closed, "closed form", case, seed)
        return started.result() if started is not None else super().closed_form(case, seed)

    def close(self) -> None:
        for queue in (self._tested, self._closed):
            queue.close()
