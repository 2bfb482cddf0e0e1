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
