"""The bounding box Mitsuba 3 gives a scene: where it places the camera of a file without a sensor
(harness/images/scene_copy.py). Mitsuba's only load of a user's file outside its renders, kept in this one
function and run, like the renders, in a worker process whose crash or hang costs this scene alone
(harness/engines/mitsuba_worker.py)."""
from __future__ import annotations

import xml.etree.ElementTree as ET

from harness.engines.mitsuba import DEFAULT_VARIANT, load_mitsuba
from harness.engines.mitsuba_worker import call_in_worker
from harness.engines.xml_lines import remove_keeping_lines


def scene_bounds(text: str, variant: str = DEFAULT_VARIANT) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """(min, max) of the scene `text` (Mitsuba 3 XML, file names absolute) as Mitsuba loads it, or None for a
    scene without shapes. Its integrators and samplers are left out (mcval's have names Mitsuba lacks; neither
    moves a shape). RuntimeError with Mitsuba's message if it cannot load the scene, RenderFailed (a
    RuntimeError) if loading it crashes or hangs Mitsuba."""
    return call_in_worker((variant, None, False), f"{__name__}:bounds_here", (text,), "while loading the scene")


def bounds_here(engine: tuple, text: str) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """In a Mitsuba worker: scene_bounds of `text` (`engine`: the arguments of the worker's MitsubaEngine)."""
    mi = load_mitsuba(engine[0])
    root = ET.fromstring(text)
    for parent in list(root.iter()):
        for e in [e for e in parent if e.tag in ("integrator", "sampler")]:
            remove_keeping_lines(parent, e)  # Mitsuba's errors then name the lines of `text`
    level = mi.log_level()
    mi.set_log_level(mi.LogLevel.Error)  # "No sensors found!" is what the caller is about to mend
    try:
        scene = mi.load_string(ET.tostring(root, encoding="unicode"), optimize=False)
    finally:
        mi.set_log_level(level)
    box = scene.bbox()
    if not box.valid():
        return None
    return tuple(float(v) for v in box.min), tuple(float(v) for v in box.max)
