"""The scene dialects an engine file may ask for (`scene_format`, docs/engines.md), each with the function that
writes a suite scene in it: (path, params, mcval's integrator, the renderer's name for it, spp) -> (the text,
width, height, other files to write beside it by name)."""
from __future__ import annotations

from pathlib import Path
from typing import Callable

from harness.engines.nori.to_nori import written_nori_scene
from harness.engines.written_scene import written_scene

Writer = Callable[[Path, dict[str, str], str, str, int], tuple[str, int, int, dict[str, str]]]


def _mitsuba(path: Path, params: dict[str, str], integrator: str, theirs: str,
             spp: int) -> tuple[str, int, int, dict[str, str]]:
    return (*written_scene(path, params, theirs, spp), {})


#: scene_format -> its writer; the first is the default.
SCENE_WRITERS: dict[str, Writer] = {"mitsuba": _mitsuba, "nori": written_nori_scene}
