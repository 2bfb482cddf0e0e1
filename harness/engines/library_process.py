"""A user's shared library (warps, BSDFs), or Mitsuba's BSDF plugins, in a process of its own
(harness/engines/python_child.py): a segfault, an abort(), a write past its output, an exit() or a hang costs the
call it happened in, named in one line with the library and what was called; a child that failed is replaced at
the next call. Calls from several threads at once each get a child of their own (started when none is idle), so
that rows checked side by side do not wait for one another."""
from __future__ import annotations

import threading
from pathlib import Path
from typing import Any, Callable

from harness.engines.python_child import ChildFailed, ChildRaised, PythonChild


class LibraryProcess:
    """The library at `path` (loaded by `child_module:load(path)` in a child; None: the module loads what it needs
    itself), whose functions `call` runs there with a time limit of `timeout()` seconds. `name` begins its
    failures' lines (default: the library's file name). Thread-safe: a call takes an idle child or starts one."""

    def __init__(self, path: Path | None, child_module: str, timeout: Callable[[], float],
                 name: str | None = None) -> None:
        self.path, self._module, self._timeout = path, child_module, timeout
        self.name = name or (path.name if path else child_module)
        self._idle: list[PythonChild] = []
        self._lock = threading.Lock()

    def _take(self) -> PythonChild:
        """An idle child that is still alive, or a new one with the library loaded."""
        with self._lock:
            while self._idle:
                child = self._idle.pop()
                if child.alive:
                    return child
        child = PythonChild()
        try:
            if self.path is not None:
                child.call(f"{self._module}:load", str(self.path), timeout=self._timeout())
        except ChildFailed as e:
            raise ChildFailed(f"{self.name}: loading it {e.reason}", e.output) from None
        except ChildRaised:
            child.close()
            raise
        return child

    def call(self, function: str, *args: Any, what: str) -> Any:
        """`function` of the child module in one of the library's processes. Raises ChildFailed, naming the
        library and `what` was called, when the call crashes, exits, hangs or writes past its output (that process
        is then ended: the next call starts another); ChildRaised for an error the library is not to blame for."""
        child = self._take()
        try:
            value = child.call(f"{self._module}:{function}", *args, timeout=self._timeout())
        except ChildFailed as e:
            raise ChildFailed(f"{self.name}: {what} {e.reason}", e.output) from None
        except ChildRaised as e:
            if e.original is not None and type(e.original).__name__ == "OutputOverrun":
                child.close()  # what it overwrote is unknown
                raise ChildFailed(f"{self.name}: {what} {e.original}") from None
            self._give(child)
            raise
        self._give(child)  # not after an interruption (Ctrl-C): PythonChild closed that child
        return value

    def _give(self, child: PythonChild) -> None:
        with self._lock:
            self._idle.append(child)
