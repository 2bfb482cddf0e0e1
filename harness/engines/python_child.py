"""Python calls in a child process: foreign code (a user's C library, Mitsuba) runs where a segfault, an
abort(), an exit() or a hang costs one call, not the run.

The child is `python -m harness.engines.python_child_main`, in its own session (a timeout ends it and all it
started), its stdout and stderr captured to a log without a name and capped. Requests and answers are pickled
frames on two pipes of their own, never on fd 1: a library that prints cannot corrupt them. A request names a
module-level function (`module:function`) and its arguments; the child keeps its modules, and their state,
between calls. subprocess, not multiprocessing: it works inside Dask's daemonic worker processes too.
"""
from __future__ import annotations

import atexit
import fcntl
import math
import os
import pickle
import select
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

from harness.engines.base import RenderFailed
from harness.engines.child_process import (OUTPUT_LIMIT, cancelled, child_env, kill_group, output_tail,
                                           signal_name)

_POLL_MS = 200
_HEADER = 8
_PIPE_BYTES = 1 << 20
#: The log is emptied before a call once it holds this much: only one call's lines are read.
_LOG_KEEP = 1 << 20
#: The folder that holds the `harness` package: the child imports it from there, wherever it was started.
_ROOT = str(Path(__file__).resolve().parents[2])


class ChildFailed(RenderFailed):
    """The child died, was killed, outlived its time limit, printed without end or answered nonsense.
    `reason` is one line without a subject ("was killed by SIGSEGV", "exited with status 0", "timed out after
    5 s"): the caller names the library and the function. The child is gone."""


class ChildRaised(Exception):
    """The called function raised: `reason` is "Type: message" (the exception itself where it pickles, as
    `original`). The child lives on."""

    def __init__(self, reason: str, original: BaseException | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.original = original


def seconds_from_env(name: str, default: float) -> float:
    """A time limit: $`name` if set (a positive number of seconds), else `default`. ValueError otherwise."""
    text = os.environ.get(name)
    if not text:
        return default
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name}={text!r}: give a positive number of seconds")
    return value


def frame(obj: Any) -> bytes:
    """A frame: the pickle's length as 8 bytes, then the pickle."""
    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    return len(data).to_bytes(_HEADER, "little") + data


class PythonChild:
    """One child process and its pipes; `call` runs a function in it. Not thread-safe: one caller at a time."""

    def __init__(self) -> None:
        self.log = tempfile.TemporaryFile(prefix="mcval-child-")
        # Appending (the child shares this open file): emptying it between calls leaves no hole.
        fcntl.fcntl(self.log.fileno(), fcntl.F_SETFL, fcntl.fcntl(self.log.fileno(), fcntl.F_GETFL) | os.O_APPEND)
        request_r, self._request = os.pipe()
        self._answer, answer_w = os.pipe()
        env = child_env()
        env["PYTHONPATH"] = os.pathsep.join(p for p in (_ROOT, env.get("PYTHONPATH")) if p)
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-m", "harness.engines.python_child_main", str(request_r), str(answer_w)],
                stdin=subprocess.DEVNULL, stdout=self.log, stderr=self.log, pass_fds=(request_r, answer_w),
                cwd=tempfile.gettempdir(), start_new_session=True, env=env)
        except OSError as e:
            self._close_fds()
            raise ChildFailed(f"could not be started: {e}") from None
        finally:
            os.close(request_r)
            os.close(answer_w)
        os.set_blocking(self._request, False)
        for fd in (self._request, self._answer):
            try:  # a million samples cross in 16 writes rather than 256
                fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, _PIPE_BYTES)
            except OSError:
                pass
        _children.add(self)

    @property
    def alive(self) -> bool:
        return self.proc.returncode is None and self.proc.poll() is None

    def call(self, function: str, *args: Any, timeout: float, cancel: threading.Event | None = None) -> Any:
        """`module:function(*args)` in the child, and what it returned. Raises ChildRaised when it raised,
        ChildFailed (the child then ended) when the child dies, outlives `timeout` seconds (then SIGKILL of
        its session), prints more than OUTPUT_LIMIT bytes, or `cancel` is set."""
        if self.proc.returncode is not None:
            raise ChildFailed("was not running")
        if os.fstat(self.log.fileno()).st_size > _LOG_KEEP:
            os.ftruncate(self.log.fileno(), 0)
        self.start = os.fstat(self.log.fileno()).st_size
        deadline = time.monotonic() + timeout
        try:
            self._send(frame((function, args)), deadline, timeout, cancel)
            answer = self._receive(deadline, timeout, cancel)
        except ChildFailed:
            raise
        except BaseException:  # interrupted mid-call (Ctrl-C): its next answer would be this call's
            self.close()
            raise
        try:
            status, value = pickle.loads(answer)
        except Exception as e:
            raise self._ended(f"answered what cannot be read ({type(e).__name__}: {e})") from None
        if status == "ok":
            return value
        reason, original = value
        raise ChildRaised(reason, original)

    def _wait(self, events: int, fd: int, deadline: float, timeout: float, cancel) -> None:
        """Until `fd` is ready for `events`; raises ChildFailed on a timeout, cancel or endless output."""
        poller = select.poll()
        poller.register(fd, events)
        while True:
            left = deadline - time.monotonic()
            if poller.poll(max(min(_POLL_MS, int(left * 1000)), 1)):
                return
            if cancelled(cancel):
                raise self._ended("was cancelled")
            if time.monotonic() >= deadline:
                if self.proc.poll() is not None:
                    raise self._died()
                raise self._ended(f"timed out after {timeout:g} s and was killed")
            if os.fstat(self.log.fileno()).st_size - self.start > OUTPUT_LIMIT:
                raise self._ended(f"printed more than {OUTPUT_LIMIT >> 20} MB and was killed")

    def _send(self, data: bytes, deadline: float, timeout: float, cancel) -> None:
        view = memoryview(data)
        while view:
            self._wait(select.POLLOUT, self._request, deadline, timeout, cancel)
            try:
                view = view[os.write(self._request, view[:1 << 20]):]
            except BlockingIOError:
                continue
            except OSError:  # EPIPE: it died before it read the request
                raise self._died() from None

    def _read(self, size: int, deadline: float, timeout: float, cancel) -> bytes:
        chunks, left = [], size
        while left:
            self._wait(select.POLLIN, self._answer, deadline, timeout, cancel)
            data = os.read(self._answer, min(left, 1 << 20))
            if not data:
                raise self._died()
            chunks.append(data)
            left -= len(data)
        return b"".join(chunks)

    def _receive(self, deadline: float, timeout: float, cancel) -> bytes:
        size = int.from_bytes(self._read(_HEADER, deadline, timeout, cancel), "little")
        return self._read(size, deadline, timeout, cancel)

    def tail(self) -> str:
        """The last lines the child printed since the current (or last) call began."""
        return output_tail(self.log, start=getattr(self, "start", 0))

    def _ended(self, reason: str) -> ChildFailed:
        failure = ChildFailed(reason, self.tail())
        self.close()
        return failure

    def _died(self) -> ChildFailed:
        kill_group(self.proc)  # what it started dies with it; reaps it, keeping its own exit status
        code = self.proc.returncode
        if code < 0:
            return self._ended(f"was killed by {signal_name(-code)}")
        tail = self.tail()
        last = f": {tail.splitlines()[-1].strip()}" if tail else ""
        return self._ended(f"exited with status {code}{last}")

    def _close_fds(self) -> None:
        for fd in (self._request, self._answer):
            try:
                os.close(fd)
            except OSError:
                pass
        self._request = self._answer = -1

    def close(self) -> None:
        """End the child (SIGKILL of its session: an idle one has nothing to lose) and close its pipes and log."""
        if self.proc.returncode is None:  # once reaped, its process id may belong to another
            kill_group(self.proc)
        self._close_fds()
        self.log.close()
        _children.discard(self)


_children: set[PythonChild] = set()


def _forget_in_fork() -> None:
    # A forked process drops its copies of the parent's pipes (the children must still see their end) and
    # never kills the parent's children.
    for child in list(_children):
        child._close_fds()
        child.proc.returncode = 0
    _children.clear()


os.register_at_fork(after_in_child=_forget_in_fork)


@atexit.register
def close_children() -> None:
    """End every child of this process."""
    for child in list(_children):
        child.close()
