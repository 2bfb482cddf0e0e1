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
    from harness.integrators import entry
    return tuple(name for _, name, _ in entry(integrator).parameters)


def _mitsuba(path: Path, params: dict[str, str], integrator: str, theirs: str,
             spp: int) -> tuple[str, int, int, dict[str, str]]:
    return (*written_scene(path, params, theirs, spp, (integrator, _parameter_names(integrator))), {})


#: scene_format -> its writer; the first is the default.
SCENE_WRITERS: dict[str, Writer] = {"mitsuba": _mitsuba, "nori": written_nori_scene}


#: scene_format -> whether its writer passes the scene's own values of an integrator's parameters on, for
#: (mcval's integrator, the renderer's name for it): Mitsuba's writer copies them, in Mitsuba's names, into
#: the renderer's <integrator> (written_scene); Nori's writes the direct strategy the values select
#: (nori/to_nori.py).
READS_PARAMETERS: dict[str, Callable[[str, str], bool]] = {
    "mitsuba": lambda integrator, theirs: bool(_parameter_names(integrator)),
    "nori": reads_direct_strategy}
