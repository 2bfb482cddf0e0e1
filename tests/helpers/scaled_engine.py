"""A known-wrong twin of our renderer: every image scaled by a factor (against itself it is still a null pair;
against the closed form or Mitsuba it is biased by factor - 1)."""
from __future__ import annotations

from harness.engines.mcval import McvalEngine


class Scaled(McvalEngine):
    def __init__(self, factor: float) -> None:
        super().__init__()
        self.factor = factor

    def render(self, *args, **kwargs):
        result = super().render(*args, **kwargs)
        result.batches = result.batches * self.factor
        return result
