"""Wall seconds of a run's phases (start-up, warps, invariances, images, report), for results.json, the report's
header and the terminal: where a run's time goes, measured rather than guessed."""
from __future__ import annotations

import time
from contextlib import contextmanager

import psutil


def seconds_since_process_start() -> float:
    """Wall seconds since this process started: the interpreter, the imports and the set-up before the first
    phase (psutil reads the start time the kernel keeps)."""
    return max(0.0, time.time() - psutil.Process().create_time())


class Phases:
    """Phase name -> wall seconds, in the order they ran; "start-up" is the time before the first phase."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = {"start-up": round(seconds_since_process_start(), 2)}

    @contextmanager
    def timed(self, name: str):
        start = time.perf_counter()
        try:
            yield
        finally:
            self.seconds[name] = round(self.seconds.get(name, 0.0) + time.perf_counter() - start, 2)

    def total(self) -> float:
        return round(sum(self.seconds.values()), 2)

    def line(self) -> str:
        """One line: each phase's seconds and the total."""
        parts = " · ".join(f"{name} {s:.1f} s" for name, s in self.seconds.items())
        return f"{parts} · total {self.total():.1f} s"
