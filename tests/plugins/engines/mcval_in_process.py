"""mcval-in-process, a test-only engine: this repository's renderer through its Python module, in this
process, where the default engine runs the `render` command as a child process. It reaches the harness
through MCVAL_ENGINE_PATH=tests/plugins/engines: an engine is this one file, its class and one registry line
(ENGINE), with no edit of the harness."""
from __future__ import annotations

from harness.engines.mcval import McvalEngine
from harness.engines.registry import EngineEntry


class InProcessEngine(McvalEngine):
    """Our renderer called through mcval_renderer.render() (a crash ends the calling process)."""

    name = "mcval-in-process"

    def __init__(self, sampler: str | None = None) -> None:
        super().__init__(sampler=sampler, in_process=True)

    def version(self) -> str:
        return "this repository's renderer, in process (the mcval_renderer module)"


ENGINE = EngineEntry("mcval-in-process", lambda options: InProcessEngine(options.get("sampler")),
                     "this repository's renderer through its Python module, in process (test-only)")
