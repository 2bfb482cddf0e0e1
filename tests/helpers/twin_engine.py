"""Our renderer's test build standing in a planted wrong twin (tests/cpp/*_twins_integrator.cpp) wherever the
harness asks for the integrator it imitates: the image suite then judges the twin as it judges that integrator."""
from __future__ import annotations

from pathlib import Path

from harness.engines.mcval import McvalEngine

TEST_RENDER = Path(__file__).resolve().parents[2] / "build" / "render_with_test_integrators"


class TwinEngine(McvalEngine):
    """Renders `twin` wherever the harness asks for `imitated` (no twin: `imitated` itself). A scene whose
    <integrator> is `imitated` (a strategy's settings, path's max_depth) is given to the twin retyped, in a copy
    in `copies` (never beside a scene of the project; the scenes it is used with refer to no other file), so
    that the twin reads those settings as `imitated` would."""

    def __init__(self, imitated: str, twin: str | None, copies: Path) -> None:
        super().__init__(binary=TEST_RENDER)
        self.imitated, self.twin, self.copies = imitated, twin, Path(copies)

    def __reduce__(self):
        return TwinEngine, (self.imitated, self.twin, self.copies)

    def reads_integrator_parameters(self, integrator: str) -> bool:
        """A twin reads the parameters Mitsuba's plugin has, not our renderer's own (path's strategy): its
        strategies are not compared."""
        from harness.integrators import entry
        if integrator == self.imitated and self.twin and entry(integrator).own_parameters:
            return False
        return super().reads_integrator_parameters(integrator)

    def render(self, scene, integrator, spp, batches, seed, params=None):
        if integrator == self.imitated and self.twin:
            text = Path(scene).read_text()
            own = f'<integrator type="{self.imitated}"'
            if own in text:
                copy = self.copies / f"{Path(scene).stem}-{self.twin}.xml"
                copy.write_text(text.replace(own, f'<integrator type="{self.twin}"'))
                scene = str(copy)
            integrator = self.twin
        return super().render(scene, integrator, spp, batches, seed, params)
