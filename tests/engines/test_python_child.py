"""A Python call in a child process (harness/engines/python_child.py): values and exceptions come back, what
the child prints stays off the answers, and a child that dies, exits or ignores SIGTERM past its time limit
fails that call in one line, also from a daemonic process (as Dask's workers are)."""
import multiprocessing
import signal
import time

import pytest

from harness.engines.python_child import ChildFailed, ChildRaised, PythonChild


@pytest.fixture
def child():
    c = PythonChild()
    yield c
    c.close()


def test_a_call_returns_its_value_and_printing_does_not_reach_the_answers(child):
    assert child.call("builtins:print", "x" * 100_000, timeout=30) is None  # on its stdout, the log
    assert child.tail().endswith("xxxx")
    assert child.call("math:hypot", 3.0, 4.0, timeout=30) == 5.0


def test_an_exception_comes_back_and_the_child_lives_on(child):
    with pytest.raises(ChildRaised, match="ValueError: math domain error"):
        child.call("math:sqrt", -1.0, timeout=30)
    assert child.call("math:sqrt", 4.0, timeout=30) == 2.0


def test_a_signal_and_an_exit_are_named(child):
    pid = child.call("os:getpid", timeout=30)
    with pytest.raises(ChildFailed, match="^was killed by SIGSEGV$"):
        child.call("os:kill", pid, signal.SIGSEGV, timeout=30)
    assert not child.alive
    other = PythonChild()
    with pytest.raises(ChildFailed, match="^exited with status 0$"):
        other.call("os:_exit", 0, timeout=30)


def test_a_call_that_ignores_sigterm_is_killed_at_its_time_limit(child):
    child.call("signal:signal", signal.SIGTERM, signal.SIG_IGN, timeout=30)
    start = time.monotonic()
    with pytest.raises(ChildFailed, match="^timed out after 0.5 s and was killed$"):
        child.call("time:sleep", 60, timeout=0.5)
    assert time.monotonic() - start < 5 and not child.alive


def _in_daemon(queue):
    child = PythonChild()
    try:
        queue.put(child.call("math:hypot", 5.0, 12.0, timeout=30))
    finally:
        child.close()


def test_it_runs_in_a_daemonic_process():
    # Dask's worker processes are daemonic: multiprocessing refuses them children, subprocess does not.
    queue = multiprocessing.get_context("spawn").Queue()
    process = multiprocessing.get_context("spawn").Process(target=_in_daemon, args=(queue,), daemon=True)
    process.start()
    assert queue.get(timeout=60) == 13.0
    process.join(30)
