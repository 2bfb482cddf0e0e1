"""Tasks on threads (harness/distributed/executor.py, ThreadExecutor): they run at once, their outcomes come back
in the order given whatever order they finish in, progress reaches every task, and a task that raises raises."""
import threading
import time

import pytest

from harness.distributed.executor import SerialExecutor, ThreadExecutor, Task


def _after(seconds: float, value):
    time.sleep(seconds)
    return value


def test_outcomes_keep_the_order_given_and_progress_reaches_every_task():
    statuses = []
    tasks = [Task(f"t{i}", _after, (0.3 - 0.1 * i, i)) for i in range(3)]  # the last finishes first
    outcomes = ThreadExecutor(3).run(tasks, lambda s: statuses.append((s.done, s.last)))
    assert [o.value for o in outcomes] == [0, 1, 2] and all(o.ok for o in outcomes)
    assert statuses[-1] == (3, "t0") and [d for d, _ in statuses] == [0, 1, 2, 3]


def test_two_slots_run_two_tasks_at_once():
    barrier = threading.Barrier(2, timeout=30)  # one task alone at it would break it
    outcomes = ThreadExecutor(2).run([Task(f"t{i}", barrier.wait) for i in range(2)])
    assert sorted(o.value for o in outcomes) == [0, 1]
    with pytest.raises(threading.BrokenBarrierError):  # the twin: one task at a time never meets the other
        SerialExecutor().run([Task("alone", threading.Barrier(2, timeout=0.5).wait)])


def test_a_task_that_raises_raises_here():
    def boom():
        raise KeyError("x")
    with pytest.raises(KeyError):
        ThreadExecutor(2).run([Task("ok", _after, (0.0, 1)), Task("boom", boom)])
