"""Where the command line writes: the console for tables, stderr for progress bars."""
from __future__ import annotations

import sys

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

# Logs (CI, pipes) get a wide table rather than a truncated one.
console = Console(width=None if sys.stdout.isatty() else 120)
err = Console(stderr=True)


def progress_bar(label: str) -> Progress:
    return Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TextColumn("{task.description}"),
                    TimeElapsedColumn(), console=err, transient=True)
