"""The scene dialects an engine file may ask for (`scene_format`, docs/engines.md), each with the function that
writes a suite scene in it: (path, params, mcval's integrator, the renderer's name for it, spp) -> (the text,
width, height, other files to write beside it by name)."""
from __future__ import annotations

from pathlib import Path
from typing import Callable

from harness.engines.nori.to_nori import reads_direct_strategy, written_nori_scene
from harness.engines.written_scene import written_scene

Writer = Callable[[Path, dict[str, str], str, str, int], tuple[str, int, int, dict[str, str]]]


def _parameter_names(integrator: str) -> tuple[str, ...]:
    """The parameters a renderer of the scene format reads, in its names (not mcval's own, such as path's
    strategy, which a renderer that follows Mitsuba does not know)."""
    from harness.integrators import entry
    return tuple(name for _, name, _ in entry(integrator).common_parameters())


def _mitsuba(path: Path, params: dict[str, str], integrator: str, theirs: str,
             spp: int) -> tuple[str, int, int, dict[str, str]]:
    return (*written_scene(path, params, theirs, spp, (integrator, _parameter_names(integrator))), {})


#: scene_format -> its writer; the first is the default.
SCENE_WRITERS: dict[str, Writer] = {"mitsuba": _mitsuba, "nori": written_nori_scene}


def _passes_every_parameter(integrator: str) -> bool:
    """Whether Mitsuba's writer passes every parameter of the integrator on: it has some, and none of mcval's own."""
    from harness.integrators import entry
    e = entry(integrator)
    return bool(e.parameters) and not e.own_parameters


#: scene_format -> whether its writer passes the scene's own values of every parameter of an integrator on, for
#: (mcval's integrator, the renderer's name for it): Mitsuba's writer copies them, in Mitsuba's names, into
#: the renderer's <integrator> (written_scene), all but mcval's own (path's strategy); Nori's writes the
#: direct strategy the values select (nori/to_nori.py).
READS_PARAMETERS: dict[str, Callable[[str, str], bool]] = {
    "mitsuba": lambda integrator, theirs: _passes_every_parameter(integrator),
    "nori": reads_direct_strategy}
