"""Progress for a log: when stderr is not a terminal (CI, a pipe, a file), a bar cannot redraw itself, so
progress is plain lines instead, at most one every PERIOD seconds (and the last one always), each saying
what is done of what and what runs."""
from __future__ import annotations

import time

from rich.console import Console

#: Seconds between two progress lines in a log.
PERIOD = 10.0


class PlainProgress:
    """The part of rich's Progress the commands use (add_task, update, console), as lines in a log."""

    def __init__(self, label: str, console: Console) -> None:
        self.label, self.console = label, console
        self._tasks: dict[int, dict] = {}
        self._start = time.monotonic()
        self._last = -PERIOD

    def __enter__(self) -> "PlainProgress":
        return self

    def __exit__(self, *exc) -> None:
        return None

    def add_task(self, description: str, total: float | None = None, **fields) -> int:
        self._tasks[len(self._tasks)] = {"description": description, "total": total, "completed": 0, **fields}
        return len(self._tasks) - 1

    def update(self, task: int, advance: float = 0, completed: float | None = None, description: str | None = None,
               **fields) -> None:
        state = self._tasks[task]
        state["completed"] = state["completed"] + advance if completed is None else completed
        if description is not None:
            state["description"] = description
        state.update(fields)
        now = time.monotonic()
        finished = state["total"] is not None and state["completed"] >= state["total"]
        if now - self._last >= PERIOD or finished:
            self._last = now
            total = "" if state["total"] is None else f"/{state['total']:g}"
            what = " · ".join(str(x) for x in (state.get("state"), state["description"]) if x)
            self.console.print(f"{self.label}: {state['completed']:g}{total} done, {now - self._start:.0f} s"
                               + (f" · {what}" if what else ""), soft_wrap=True, highlight=False, markup=False)
