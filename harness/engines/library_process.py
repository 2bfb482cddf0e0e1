"""A user's shared library (warps, BSDFs), or Mitsuba's BSDF plugins, in a process of its own
(harness/engines/python_child.py): a segfault, an abort(), a write past its output, an exit() or a hang costs the
call it happened in, named in one line with the library and what was called; a child that failed is replaced at
the next call."""
from __future__ import annotations

from pathlib import Path
from typing import Any, Callable

from harness.engines.python_child import ChildFailed, ChildRaised, PythonChild


class LibraryProcess:
    """The library at `path` (loaded by `child_module:load(path)` in a child; None: the module loads what it needs
    itself), whose functions `call` runs there with a time limit of `timeout()` seconds. `name` begins its
    failures' lines (default: the library's file name)."""

    def __init__(self, path: Path | None, child_module: str, timeout: Callable[[], float],
                 name: str | None = None) -> None:
        self.path, self._module, self._timeout = path, child_module, timeout
        self.name = name or (path.name if path else child_module)
        self._child: PythonChild | None = None

    def call(self, function: str, *args: Any, what: str) -> Any:
        """`function` of the child module in the library's process (started if there is none). Raises
        ChildFailed, naming the library and `what` was called, when the call crashes, exits, hangs or writes
        past its output (the process is then ended: the next call starts another); ChildRaised for an error
        the library is not to blame for."""
        if self._child is None or not self._child.alive:
            child = PythonChild()
            try:
                if self.path is not None:
                    child.call(f"{self._module}:load", str(self.path), timeout=self._timeout())
            except ChildFailed as e:
                raise ChildFailed(f"{self.name}: loading it {e.reason}", e.output) from None
            except ChildRaised:
                child.close()
                raise
            self._child = child
        try:
            return self._child.call(f"{self._module}:{function}", *args, timeout=self._timeout())
        except ChildFailed as e:
            self._child = None
            raise ChildFailed(f"{self.name}: {what} {e.reason}", e.output) from None
        except ChildRaised as e:
            if e.original is not None and type(e.original).__name__ == "OutputOverrun":
                self._child.close()  # what it overwrote is unknown
                self._child = None
                raise ChildFailed(f"{self.name}: {what} {e.original}") from None
            raise
