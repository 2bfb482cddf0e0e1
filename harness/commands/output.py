"""Where the commands write: the console for tables, stderr for progress bars."""
from __future__ import annotations

import os
import sys
from contextlib import contextmanager

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from harness.commands.plain_progress import PlainProgress
from harness.verdict import Verdict

#: Width of tables in a log (CI, a pipe) when $COLUMNS does not say: wide enough that none is cut.
LOG_WIDTH = 200


def _width() -> int | None:
    """$COLUMNS if set, else the terminal's, else LOG_WIDTH."""
    if os.environ.get("COLUMNS", "").isdigit():
        return int(os.environ["COLUMNS"])
    return None if sys.stdout.isatty() else LOG_WIDTH


console = Console(width=_width())
err = Console(stderr=True)


def progress_bar(label: str):
    """A bar on a terminal; plain lines in a log."""
    if not err.is_terminal:
        return PlainProgress(label, err)
    return Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TextColumn("{task.description}"),
                    TimeElapsedColumn(), console=err, transient=True)


@contextmanager
def task_progress(label: str, executor):
    """A progress line for tasks on `executor`: done of total, running, failed, time left; yields the
    callback that executors call with their Status."""
    columns = (TextColumn(f"{label} ({executor.description})"), BarColumn(), MofNCompleteColumn(),
               TextColumn("{task.fields[state]}"), TimeElapsedColumn())
    shown = Progress(*columns, console=err, transient=True) if err.is_terminal else \
        PlainProgress(f"{label} ({executor.description})", err)
    with shown as progress:
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


def print_verdict(results, verdict: Verdict, reason: str = "") -> None:
    """A run's last line, `Results: <results.json> — PASS`, after the line that says why nothing was judged."""
    if reason:
        console.print(f"[red]FAIL[/] {escape(reason)}", soft_wrap=True)
    shown = "FAIL (nothing was judged)" if verdict is Verdict.NOTHING_JUDGED else verdict.value
    console.print(f"Results: {results} — {shown}")
