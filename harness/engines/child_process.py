"""A renderer as a child process: its own session (a timeout or Ctrl-C ends it and everything it started),
its output captured to a file and capped, and every way it can go wrong turned into one RenderFailed line with
the last lines of what it printed. Every process it started ends when it does, a daemon that left its session
included: each call's environment carries a token of its own (CALL_TOKEN_ENV), which the harness looks for."""
from __future__ import annotations

import os
import signal
import subprocess
import threading
import uuid
from contextlib import contextmanager, nullcontext
from pathlib import Path
from typing import BinaryIO

import psutil

from harness.engines.base import RenderFailed
from harness.foreign_text import foreign

#: Output a call may print before it is ended: a renderer printing without end must not fill the disk.
OUTPUT_LIMIT = 64 << 20
#: Lines of a failed call's output kept for the report.
TAIL_LINES = 50
_POLL_SECONDS = 0.2
#: The environment variable that marks every process one call started, with a value of that call's own.
CALL_TOKEN_ENV = "MCVAL_CALL_TOKEN"
_thread = threading.local()


@contextmanager
def cancelled_by(event: threading.Event | None):
    """Children this thread runs within the block end (RenderFailed "cancelled") once `event` is set: how a
    thread rendering for another one (harness/engines/render_thread.py) is stopped when that one is
    interrupted. Nested, the outer block's event holds again after the inner one."""
    previous = current_cancel()
    _thread.cancel = event
    try:
        yield
    finally:
        _thread.cancel = previous


def current_cancel() -> threading.Event | None:
    """The event this thread's renders are cancelled by (cancelled_by), if any."""
    return getattr(_thread, "cancel", None)


def cancelled(cancel: threading.Event | None = None) -> bool:
    """Whether `cancel`, or the event this thread's renders are cancelled by (cancelled_by), is set."""
    outer = current_cancel()
    return (cancel is not None and cancel.is_set()) or (outer is not None and outer.is_set())


def child_env() -> dict[str, str]:
    """A copy of this process's environment for a child. Started from a thread, a child given none reads the
    live environment between vfork and exec, where another thread setting a variable (an import's
    os.environ.setdefault) makes exec fail with EFAULT ("Bad address")."""
    return dict(os.environ)


def kill_group(proc: subprocess.Popen) -> None:
    """SIGKILL the child and everything it started (its own session), then reap it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    proc.wait()


def end_marked(token: str) -> int:
    """SIGKILL every process whose environment holds CALL_TOKEN_ENV = `token`: what a call left running after
    it ended (a daemon, double-forked into a session of its own, is out of the reach of kill_group). Returns
    how many were ended. A process that cleared its environment cannot be found this way."""
    ended = 0
    for proc in psutil.process_iter():
        try:
            if proc.pid != os.getpid() and proc.environ().get(CALL_TOKEN_ENV) == token:
                proc.kill()
                ended += 1
        except (psutil.NoSuchProcess, psutil.AccessDenied, psutil.ZombieProcess):
            pass  # gone meanwhile, or not this process's to read
    return ended


def signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return "an unknown signal"


def output_tail(log: Path | BinaryIO, lines: int = TAIL_LINES, start: int = 0) -> str:
    """The last `lines` non-empty lines of a log (a path, or a binary file open for reading) after byte
    `start` (read from its end only), as foreign text (bounded and safe: harness/foreign_text.py)."""
    with open(log, "rb") if isinstance(log, (str, Path)) else nullcontext(log) as f:
        f.seek(max(start, f.seek(0, os.SEEK_END) - 256 * lines))
        text = f.read().decode(errors="replace")
    kept = [line.rstrip() for line in text.splitlines() if line.strip()]
    return foreign("\n".join(kept[-lines:]), keep="tail")


def run_child(command: list[str], cwd: Path, log: Path, timeout: float, cancel: threading.Event | None = None,
              output_limit: int | None = None) -> None:
    """Run `command` in `cwd`, its stdout and stderr into `log`. Returns when it exits with status 0; raises
    RenderFailed when it exits otherwise, is killed, outlives `timeout` seconds, prints more than
    `output_limit` bytes (default OUTPUT_LIMIT; `output` holding its last lines) or `cancel` (or this thread's
    cancelled_by event) is set (another thread was interrupted: the child, in its own session, would not see
    the Ctrl-C); OSError if it cannot be started. Whatever it started and left running is ended (end_marked)."""
    token = uuid.uuid4().hex
    with open(log, "wb") as log_file:
        proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=log_file, stderr=subprocess.STDOUT,
                                cwd=cwd, start_new_session=True, env={**child_env(), CALL_TOKEN_ENV: token})
        waited = 0.0
        try:
            while True:
                try:
                    code = proc.wait(timeout=min(_POLL_SECONDS, max(timeout - waited, 0.001)))
                    break
                except subprocess.TimeoutExpired:
                    waited += _POLL_SECONDS
                    if cancelled(cancel):
                        kill_group(proc)
                        raise RenderFailed("cancelled", output_tail(log)) from None
                    if waited >= timeout:
                        kill_group(proc)
                        raise RenderFailed(f"timed out after {timeout:g} s", output_tail(log)) from None
                    limit = OUTPUT_LIMIT if output_limit is None else output_limit
                    if log.stat().st_size > limit:
                        kill_group(proc)
                        raise RenderFailed(f"printed more than {limit / 2**20:g} MB and was ended",
                                           output_tail(log)) from None
        except BaseException:
            if proc.poll() is None:
                kill_group(proc)
            raise
        finally:
            end_marked(token)
    if code < 0:
        raise RenderFailed(f"killed by signal {signal_name(-code)} ({-code})", output_tail(log))
    if code > 0:
        tail = output_tail(log)
        last = tail.splitlines()[-1].strip() if tail else "(no error message)"
        raise RenderFailed(f"exited with status {code}: {last}", tail)
