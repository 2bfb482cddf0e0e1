"""An engine for the worker-death test, importable by name on a Dask worker (the project root is on its path)."""
from __future__ import annotations

import os

from harness.engines.mcval import McvalEngine


class DiesOn(McvalEngine):
    """Our renderer, except that rendering `integrator` ends the whole process at once, as a crash of an
    engine that renders inside the worker (Mitsuba) would."""

    def __init__(self, integrator: str) -> None:
        super().__init__()
        self.fatal = integrator

    def __reduce__(self):
        return DiesOn, (self.fatal,)

    def render(self, scene, integrator, spp, batches, seed, params=None):
        if integrator == self.fatal:
            os._exit(3)
        return super().render(scene, integrator, spp, batches, seed, params)
