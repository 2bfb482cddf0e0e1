"""A library's processes (harness/engines/library_process.py) under calls from several threads: calls at once
each get a child of their own, a child left idle is used again, and a crash fails the call it happened in while
the other thread's call returns."""
from concurrent.futures import ThreadPoolExecutor

import pytest

from harness.engines.library_process import LibraryProcess
from harness.engines.python_child import ChildFailed


def _process() -> LibraryProcess:
    return LibraryProcess(None, "tests.helpers.child_calls", lambda: 60.0, name="calls")


def test_calls_at_once_get_a_child_each_and_an_idle_one_is_used_again():
    process = _process()
    with ThreadPoolExecutor(2) as pool:
        pids = list(pool.map(lambda _: process.call("pid_after", 1.0, what="pid_after"), range(2)))
    assert len(set(pids)) == 2  # the second call did not wait for the first one's child
    assert process.call("pid_after", 0.0, what="pid_after") in pids


def test_a_crash_fails_its_own_call_and_the_other_thread_goes_on():
    process = _process()
    with ThreadPoolExecutor(2) as pool:
        crashed = pool.submit(process.call, "crash_after", 0.5, what="crash_after")
        answered = pool.submit(process.call, "pid_after", 1.0, what="pid_after")
        with pytest.raises(ChildFailed, match="^calls: crash_after was killed by SIGSEGV$"):
            crashed.result()
        survivor = answered.result()
    assert process.call("pid_after", 0.0, what="pid_after") == survivor  # the crashed child is not used again
