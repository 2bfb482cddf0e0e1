"""Long-lived `render --serve` children, one per binary and process, that render request after request.

A render in a child process of its own keeps a crash, a kill or a hang away from the harness, but on a
small render the process, its thread pool and its first touch of memory cost as much as the render. A
worker keeps all three between renders and keeps the isolation: a worker that dies or outlives its
timeout fails that render alone (one RenderFailed line) and is replaced on the next. Workers live in
their own session, so that ending one ends what it started; one whose caller dies reads the end of its
input and exits.
"""
from __future__ import annotations

import atexit
import os
import select
import shutil
import subprocess
import tempfile
import threading
from pathlib import Path

from harness.engines.base import RenderFailed
from harness.engines.child_process import OUTPUT_LIMIT, kill_group, output_tail, signal_name

_POLL_SECONDS = 0.2
#: A worker's log is emptied before a render once it holds this much: only one render's lines are read.
_LOG_KEEP = 1 << 20


def frame_request(args: list[str]) -> bytes:
    """A request as `render --serve` reads it: the argument count on a line, then each argument's length
    in bytes on a line followed by its bytes."""
    out = [f"{len(args)}\n".encode()]
    for arg in args:
        data = arg.encode()
        out += [f"{len(data)}\n".encode(), data]
    return b"".join(out)


def last_line(tail: str) -> str:
    """A failure's message: the last line it printed."""
    return tail.splitlines()[-1].strip() if tail else "(no error message)"


class RenderWorker:
    """One `BINARY --serve` child in a temporary folder of its own (its working folder and log)."""

    def __init__(self, binary: Path) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="mcval-worker-"))
        self.log = self.folder / "output.txt"
        with open(self.log, "ab") as log:  # appended to: emptying it between renders leaves no hole
            self.proc = subprocess.Popen([str(binary), "--serve"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         stderr=log, cwd=self.folder, start_new_session=True)
        self._pending = b""
        self.start = 0  # where the last render's output starts in the log

    @property
    def alive(self) -> bool:
        return self.proc.poll() is None

    def call(self, args: list[str], timeout: float, cancel: threading.Event | None = None) -> int:
        """Run one render and return its exit status. Raises RenderFailed (and ends the worker) when the worker
        dies, outlives `timeout` seconds, prints more than OUTPUT_LIMIT bytes or `cancel` is set."""
        if self.log.stat().st_size > _LOG_KEEP:
            os.truncate(self.log, 0)
        start = self.start = self.log.stat().st_size
        try:
            self.proc.stdin.write(frame_request(args))
            self.proc.stdin.flush()
        except (BrokenPipeError, OSError):
            raise self._died(start) from None
        fd, waited = self.proc.stdout.fileno(), 0.0
        while b"\n" not in self._pending:
            ready, _, _ = select.select([fd], [], [], min(_POLL_SECONDS, max(timeout - waited, 0.001)))
            if ready:
                data = os.read(fd, 4096)
                if not data:
                    raise self._died(start)
                self._pending += data
                continue
            waited += _POLL_SECONDS
            if cancel is not None and cancel.is_set():
                raise self._ended("cancelled", start)
            if waited >= timeout:
                raise self._ended(f"timed out after {timeout:g} s", start)
            if self.log.stat().st_size - start > OUTPUT_LIMIT:
                raise self._ended(f"printed more than {OUTPUT_LIMIT >> 20} MB and was ended", start)
        line, self._pending = self._pending.split(b"\n", 1)
        return int(line)

    def tail(self, start: int = 0) -> str:
        """The last lines of the log after byte `start`."""
        return output_tail(self.log, start=start)

    def close(self) -> None:
        """End the worker (at once: an idle one has nothing to lose) and remove its folder."""
        if self.proc.poll() is None:
            kill_group(self.proc)
        for stream in (self.proc.stdin, self.proc.stdout):
            try:
                stream.close()
            except OSError:
                pass
        shutil.rmtree(self.folder, ignore_errors=True)

    def _ended(self, reason: str, start: int) -> RenderFailed:
        failure = RenderFailed(reason, self.tail(start))
        self.close()
        return failure

    def _died(self, start: int) -> RenderFailed:
        code = self.proc.wait()
        kill_group(self.proc)  # what it started dies with it
        if code < 0:
            return self._ended(f"killed by signal {signal_name(-code)} ({-code})", start)
        return self._ended(f"its worker exited with status {code}: {last_line(self.tail(start))}", start)


_lock = threading.Lock()
_idle: dict[tuple, list[RenderWorker]] = {}
_owner = os.getpid()


def _key(binary: Path) -> tuple:
    # A rebuilt binary is a new key: a worker never renders with the code of an older build.
    st = binary.stat()
    return str(binary), st.st_ino, st.st_mtime_ns


def run_in_worker(binary: Path, args: list[str], timeout: float, cancel: threading.Event | None = None
                  ) -> tuple[int, str]:
    """Run `binary ARGS` in an idle worker of that binary (started if there is none) and return its exit
    status and, unless it is 0, the last lines the render printed. Raises RenderFailed as RenderWorker.call."""
    global _owner
    key = _key(binary)
    with _lock:
        if os.getpid() != _owner:  # a forked child: the workers belong to its parent
            _idle.clear()
            _owner = os.getpid()
        idle = _idle.setdefault(key, [])
        worker = None
        while idle and worker is None:
            worker = idle.pop()
            if not worker.alive:
                worker.close()
                worker = None
    worker = worker or RenderWorker(binary)
    try:
        status = worker.call(args, timeout, cancel)
        tail = worker.tail(worker.start) if status else ""
    except BaseException:
        worker.close()  # interrupted mid-render (a Ctrl-C): its state is unknown
        raise
    with _lock:
        if os.getpid() == _owner:
            _idle.setdefault(key, []).append(worker)
    return status, tail


@atexit.register
def close_workers() -> None:
    """End every idle worker of this process."""
    with _lock:
        workers = [w for ws in _idle.values() for w in ws] if os.getpid() == _owner else []
        _idle.clear()
    for worker in workers:
        worker.close()
