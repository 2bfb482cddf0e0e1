"""Long-lived `render --serve` children, one per binary and process, that render request after request.

A render in a child process of its own keeps a crash, a kill or a hang away from the harness, but on a
small render the process, its thread pool and its first touch of memory cost as much as the render. A
worker keeps all three between renders and keeps the isolation: a worker that dies or outlives its
timeout fails that render alone (one RenderFailed line) and is replaced on the next. Workers live in
their own session, so that ending one ends what it started; one whose caller dies reads the end of its
input and exits. A binary that does not answer `--serve` with its greeting (an older build, a user's
script) raises NoServe, and the caller renders with it one process per render.
"""
from __future__ import annotations

import atexit
import fcntl
import os
import re
import select
import subprocess
import tempfile
import threading
from pathlib import Path

from harness.engines.base import RenderFailed
from harness.engines.child_process import (OUTPUT_LIMIT, cancelled, child_env, kill_group, output_tail,
                                           signal_name)

#: The first line `render --serve` writes: it speaks this framing.
GREETING = b"mcval-serve 1"
#: Seconds a new worker may take to greet.
START_SECONDS = 60.0
_POLL_MS = 200
#: A worker's log is emptied before a render once it holds this much: only one render's lines are read.
_LOG_KEEP = 1 << 20
_STATUS = re.compile(rb"-?[0-9]+")


class NoServe(Exception):
    """The binary did not greet as `render --serve` does: it cannot be a worker (the reason is the message)."""


def frame_request(args: list[str]) -> bytes:
    """A request as `render --serve` reads it: the argument count on a line, then each argument's length
    in bytes on a line followed by its bytes (file names in the file system's encoding)."""
    out = [f"{len(args)}\n".encode()]
    for arg in args:
        data = os.fsencode(arg)
        out += [f"{len(data)}\n".encode(), data]
    return b"".join(out)


def last_line(tail: str) -> str:
    """A failure's message: the last line it printed."""
    return tail.splitlines()[-1].strip() if tail else "(no error message)"


class RenderWorker:
    """One `BINARY --serve` child. What it prints goes to a log file without a name (nothing is left behind,
    however the harness ends), opened for appending: emptying it between renders leaves no hole."""

    def __init__(self, binary: Path) -> None:
        self.log = tempfile.TemporaryFile(prefix="mcval-worker-")
        fcntl.fcntl(self.log.fileno(), fcntl.F_SETFL, fcntl.fcntl(self.log.fileno(), fcntl.F_GETFL) | os.O_APPEND)
        self._pending = b""
        self.start = 0  # where the last render's output starts in the log
        try:
            # Its working folder is the system's temporary one: it writes only where its requests say.
            self.proc = subprocess.Popen([str(binary), "--serve"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         stderr=self.log, cwd=tempfile.gettempdir(), start_new_session=True,
                                         env=child_env())
        except OSError as e:
            self.log.close()
            raise RenderFailed(f"cannot start {binary}: {e}") from e
        try:
            greeting = self._read_line(START_SECONDS)
        except RenderFailed as e:
            raise NoServe(f"`{binary} --serve` did not start as a render worker: {e.reason}") from None
        if greeting != GREETING:
            self.close()
            raise NoServe(f"`{binary} --serve` answered {greeting[:80]!r}, not the greeting of a render worker")

    @property
    def alive(self) -> bool:
        return self.proc.poll() is None

    def call(self, args: list[str], timeout: float, cancel: threading.Event | None = None) -> int:
        """Run one render and return its exit status. Raises RenderFailed (and ends the worker) when the worker
        dies, outlives `timeout` seconds, prints more than OUTPUT_LIMIT bytes, answers something else than a
        status, or `cancel` is set."""
        if self._log_size() > _LOG_KEEP:
            os.ftruncate(self.log.fileno(), 0)
        self.start = self._log_size()
        try:
            self.proc.stdin.write(frame_request(args))
            self.proc.stdin.flush()
        except OSError:
            raise self._died() from None
        line = self._read_line(timeout, cancel)
        if not _STATUS.fullmatch(line) or self._pending:
            raise self._ended(f"answered {line[:80]!r}, not an exit status")
        return int(line)

    def _read_line(self, timeout: float, cancel: threading.Event | None = None) -> bytes:
        """The next line of the worker's answers, without its newline (see `call` for what raises)."""
        fd, waited = self.proc.stdout.fileno(), 0.0
        poller = select.poll()
        poller.register(fd, select.POLLIN)
        while b"\n" not in self._pending:
            if poller.poll(min(_POLL_MS, max(int((timeout - waited) * 1000), 1))):
                data = os.read(fd, 4096)
                if not data:
                    raise self._died()
                self._pending += data
                continue
            waited += _POLL_MS / 1000
            if cancelled(cancel):
                raise self._ended("cancelled")
            if waited >= timeout:
                raise self._ended(f"timed out after {timeout:g} s")
            if self._log_size() - self.start > OUTPUT_LIMIT:
                raise self._ended(f"printed more than {OUTPUT_LIMIT >> 20} MB and was ended")
        line, self._pending = self._pending.split(b"\n", 1)
        return line

    def _log_size(self) -> int:
        return os.fstat(self.log.fileno()).st_size

    def tail(self) -> str:
        """The last lines the worker printed since the current (or last) render began."""
        return output_tail(self.log, start=self.start)

    def close(self) -> None:
        """End the worker (at once: an idle one has nothing to lose) and close its log."""
        if self.proc.returncode is None:  # once reaped, its process id may belong to another
            kill_group(self.proc)
        self.close_pipes()
        self.log.close()

    def close_pipes(self) -> None:
        """Close this process's ends of the worker's input and answers."""
        for stream in (self.proc.stdin, self.proc.stdout):
            try:
                stream.close()
            except OSError:
                pass

    def _ended(self, reason: str) -> RenderFailed:
        failure = RenderFailed(reason, self.tail())
        self.close()
        return failure

    def _died(self) -> RenderFailed:
        kill_group(self.proc)  # what it started dies with it; reaps it, keeping its own exit status
        code = self.proc.returncode
        if code < 0:
            return self._ended(f"killed by signal {signal_name(-code)} ({-code})")
        return self._ended(f"its worker exited with status {code}: {last_line(self.tail())}")


_lock = threading.Lock()
_idle: dict[tuple, list[RenderWorker]] = {}
_no_serve: dict[tuple, str] = {}


def _forget_in_child() -> None:
    # The workers are the parent's: a forked child drops its copies of their pipes (so that they still see
    # their input end with the parent) and starts without any.
    global _lock
    _lock = threading.Lock()
    for worker in (w for ws in _idle.values() for w in ws):
        worker.close_pipes()
    _idle.clear()


os.register_at_fork(after_in_child=_forget_in_child)


def _key(binary: Path) -> tuple:
    # A rebuilt binary is a new key: a worker never renders with the code of an older build.
    st = binary.stat()
    return str(binary), st.st_ino, st.st_mtime_ns


def run_in_worker(binary: Path, args: list[str], timeout: float, cancel: threading.Event | None = None
                  ) -> tuple[int, str]:
    """Run `binary ARGS` in an idle worker of that binary (started if there is none) and return its exit
    status and, unless it is 0, the last lines the render printed. Raises RenderFailed as RenderWorker.call,
    NoServe if the binary cannot be a worker (remembered: it is not tried again)."""
    key = _key(binary)
    with _lock:
        if key in _no_serve:
            raise NoServe(_no_serve[key])
        for old in [k for k in _idle if k[0] == key[0] and k != key]:  # workers of an older build
            for worker in _idle.pop(old):
                worker.close()
        idle = _idle.setdefault(key, [])
        worker = None
        while idle and worker is None:
            worker = idle.pop()
            if not worker.alive:
                worker.close()
                worker = None
    kept = False
    try:
        if worker is None:
            try:
                worker = RenderWorker(binary)
            except NoServe as e:
                with _lock:
                    _no_serve[key] = str(e)
                raise
        status = worker.call(args, timeout, cancel)
        tail = worker.tail() if status else ""
        with _lock:
            _idle.setdefault(key, []).append(worker)
            kept = True
        return status, tail
    finally:
        if worker is not None and not kept:
            worker.close()  # failed, or interrupted mid-render (a Ctrl-C): its state is unknown


@atexit.register
def close_workers() -> None:
    """End every idle worker of this process."""
    with _lock:
        workers = [w for ws in _idle.values() for w in ws]
        _idle.clear()
    for worker in workers:
        worker.close()
