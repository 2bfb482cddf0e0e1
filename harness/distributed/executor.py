"""Running a list of independent tasks, here or on Dask, with their outcomes in the order given.

A task whose worker dies under it gives an Outcome with `error` (one line) instead of a value: the
caller fails that job and the run goes on. A task that raises raises here, wherever it ran: the jobs
catch what they expect (a failed render), so anything else is a bug and stops the run."""
from __future__ import annotations

import time
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, Callable


@dataclass
class Task:
    key: str                      # unique in a run; shown in the progress line
    fn: Callable[..., Any]        # importable by name on a worker (module-level)
    args: tuple = ()


@dataclass
class Outcome:
    value: Any = None
    error: str | None = None      # why the task gave no value

    @property
    def ok(self) -> bool:
        return self.error is None


@dataclass
class Status:
    """What a progress line shows: tasks done, running and failed, and the time left at the pace so far."""

    total: int
    done: int = 0
    failed: int = 0
    running: int = 0
    started: float = field(default_factory=time.perf_counter)
    last: str = ""                # key of the task that finished last

    def eta_seconds(self) -> float | None:
        if self.done == 0:
            return None
        return (time.perf_counter() - self.started) / self.done * (self.total - self.done)


class Executor(ABC):
    #: "serial", "local cluster (N workers)" or the scheduler's address: for reports.
    description: str
    #: Tasks that can run at once.
    slots: int = 1
    #: Whether tasks run where this process's files may not be: then they get their files by content.
    ships_files: bool = False

    @abstractmethod
    def run(self, tasks: list[Task], on_status: Callable[[Status], None] | None = None) -> list[Outcome]:
        """Every task's outcome, in the order of `tasks`."""

    def share(self, value: Any) -> Any:
        """A handle to `value` to pass in several tasks' args (on a cluster: sent there once)."""
        return value

    def close(self) -> None:
        pass

    def __enter__(self) -> "Executor":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class SerialExecutor(Executor):
    """One task after another in this process: no start-up cost, for small runs and for tests that
    hand in engines that cannot leave the process."""

    description = "serial"

    def run(self, tasks, on_status=None):
        status, out = Status(len(tasks)), []
        for task in tasks:
            status.running = 1
            if on_status:
                on_status(status)
            out.append(Outcome(task.fn(*task.args)))
            status.done, status.running, status.last = status.done + 1, 0, task.key
            if on_status:
                on_status(status)
        return out


class ThreadExecutor(Executor):
    """Tasks on `slots` threads of this process (concurrent.futures): for work that waits on other processes (a
    library's children, Mitsuba's) or in numpy, which let go of the interpreter, and whose arguments need not
    travel (engines of this process). Outcomes in the order given; a task that raises raises here, after the
    tasks already running have finished."""

    def __init__(self, slots: int) -> None:
        self.slots = max(int(slots), 1)
        self.description = f"{self.slots} threads"

    def run(self, tasks, on_status=None):
        from concurrent.futures import ThreadPoolExecutor, as_completed

        status = Status(len(tasks))
        with ThreadPoolExecutor(self.slots, thread_name_prefix="task") as pool:
            futures = {pool.submit(task.fn, *task.args): task for task in tasks}
            status.running = min(self.slots, len(tasks))
            if on_status:
                on_status(status)
            try:
                for future in as_completed(futures):
                    future.result()  # a task that raised: raise here
                    status.done, status.last = status.done + 1, futures[future].key
                    status.running = min(self.slots, len(tasks) - status.done)
                    if on_status:
                        on_status(status)
            except BaseException:
                for future in futures:
                    future.cancel()
                raise
        return [Outcome(future.result()) for future in futures]
