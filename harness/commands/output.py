"""Where the commands write: the console for tables, stderr for progress bars."""
from __future__ import annotations

import sys
from contextlib import contextmanager

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

# Logs (CI, pipes) get a wide table rather than a truncated one.
console = Console(width=None if sys.stdout.isatty() else 120)
err = Console(stderr=True)


def progress_bar(label: str) -> Progress:
    return Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TextColumn("{task.description}"),
                    TimeElapsedColumn(), console=err, transient=True)


@contextmanager
def task_progress(label: str, executor):
    """A progress line for tasks on `executor`: done of total, running, failed, time left; yields the
    callback that executors call with their Status."""
    columns = (TextColumn(f"{label} ({executor.description})"), BarColumn(), MofNCompleteColumn(),
               TextColumn("{task.fields[state]}"), TimeElapsedColumn())
    with Progress(*columns, console=err, transient=True) as progress:
        task = None

        def show(status) -> None:
            nonlocal task
            if task is None:
                task = progress.add_task("", total=status.total, state="")
            eta = status.eta_seconds()
            state = f"running {status.running}, failed {status.failed}" + \
                (f", about {eta:.0f} s left" if eta is not None else "") + (f" · {status.last}" if status.last else "")
            progress.update(task, completed=status.done, state=state)

        yield show
