"""A thread that renders for its caller, so that the caller can compare one image while the next renders.

For an engine whose renders run in another process (Engine.renders_elsewhere): the thread only waits on
that process. Closing it ends a render still running (RenderFailed "cancelled", the child killed): an
interrupted caller, or one that stopped early, never waits for a render nobody will read.
"""
from __future__ import annotations

import threading
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any, Callable

from harness.engines.child_process import cancelled_by


class RenderThread:
    """Runs the calls submitted to it one at a time, in order, on a thread of its own."""

    def __init__(self) -> None:
        self._pool = ThreadPoolExecutor(1, thread_name_prefix="render")
        self._cancel = threading.Event()

    def submit(self, fn: Callable[..., Any], *args: Any) -> Future:
        return self._pool.submit(self._run, fn, args)

    def _run(self, fn: Callable[..., Any], args: tuple) -> Any:
        with cancelled_by(self._cancel):
            return fn(*args)

    def close(self) -> None:
        """Drop the calls not started, end the one running, and wait for the thread."""
        self._cancel.set()
        self._pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self) -> "RenderThread":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
