"""The prepared copy of a Mitsuba 3 scene file given with --scene (harness/images/user_scenes.py): what every
case of the suite sets, written one element a line, with the line of the user's file each line came from.

What the copy sets, and what it refuses (one SceneXmlError naming the file, the line and the element):
- every <default> needs a name and a value;
- the film's width and height are whole numbers of pixels (at least 1); its size becomes $res, declared as the
  run's resolution, the height keeping the aspect; its crop window is scaled with it;
- a sensor without a film gets Mitsuba's default one (768 x 576) at the run's resolution;
- a file without a sensor gets the camera Mitsuba made for one until 3.0.0 (src/render/scene.cpp before
  commit 1279b88, as Mitsuba 0.6 did: a 45 degree perspective camera looking along +z from before the
  scene's bounding box), written out, so that both engines render the same view; Mitsuba 3.0.0 and later make
  none (`mi.render` then has no sensor to render from), so the copy says so in a note;
- every file a `filename` names must exist (one refusal for the scene, not one per case).
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

from harness.engines.nori.lined_xml import LinedXml, SceneXmlError, parse_lined
from harness.engines.scene_paths import absolute_paths
from harness.images.copy_lines import name_lines

#: Mitsuba's hdrfilm without a width or height (its default film).
MITSUBA_FILM = (768, 576)
#: The camera Mitsuba made for a scene without one until 3.0.0: its field of view, in degrees.
DEFAULT_FOV = 45.0
#: The tallest film the copy takes, over its width: its height follows the run's width.
MAX_ASPECT = 16
_CROP = (("crop_offset_x", 0), ("crop_offset_y", 0), ("crop_width", None), ("crop_height", None))


@dataclass
class Prepared:
    """The copy's text and, per line of it, the line of the user's file it came from (0: none)."""

    text: str
    source_lines: list[int] = field(default_factory=list)


def _fail(doc: LinedXml, e: ET.Element, why: str) -> SceneXmlError:
    attrs = "".join(f' {k}="{v if len(v) <= 80 else v[:80] + "..."}"' for k, v in e.attrib.items())
    return SceneXmlError(f"{doc.where(e)}: <{e.tag[:40]}{attrs}>: {why}")


def _defaults(doc: LinedXml) -> dict[str, str]:
    """The file's <default>s; SceneXmlError for one without a name or a value (Mitsuba refuses both)."""
    values = {}
    for e in (e for e in doc.root if e.tag == "default"):
        if not e.get("name") or e.get("value") is None:
            raise _fail(doc, e, "a <default> needs a name and a value")
        values[e.get("name")] = e.get("value")
    return values


#: The largest film size or crop value a file may give: Mitsuba reads an <integer> as a 64-bit one.
MOST_PIXELS = 2**63 - 1


def _pixels(doc: LinedXml, e: ET.Element, defaults: dict[str, str], least: int = 1) -> int:
    """The whole number of pixels `e` gives ($name through the file's defaults)."""
    value = (e.get("value") or "").strip()
    if value.startswith("$"):
        value = defaults.get(value[1:], value)
    try:
        number = int(value)
    except ValueError:
        raise _fail(doc, e, "expected a whole number of pixels") from None
    if number < least:
        raise _fail(doc, e, f"expected at least {least} pixel{'s' if least != 1 else ''}")
    if number > MOST_PIXELS:
        raise _fail(doc, e, f"expected at most {MOST_PIXELS} pixels")
    return number


def _size_film(doc: LinedXml, film: ET.Element, defaults: dict[str, str], resolution: int) -> None:
    """The film's width as $res and its height keeping the aspect; its crop window scaled alike (in place)."""
    given = {e.get("name"): e for e in film if e.tag == "integer"}
    width = _pixels(doc, given["width"], defaults) if "width" in given else MITSUBA_FILM[0]
    height = _pixels(doc, given["height"], defaults) if "height" in given else MITSUBA_FILM[1]
    scale = resolution / width
    new_height = max(1, round(height * scale))
    if new_height > MAX_ASPECT * resolution:
        raise _fail(doc, film, f"a film {height / width:.3g} times as tall as wide would be {resolution} x "
                               f"{new_height} pixels at the run's resolution (at most {MAX_ASPECT} times as tall)")
    crop = {name: _pixels(doc, given[name], defaults, least=0 if default == 0 else 1) if name in given else default
            for name, default in _CROP}
    for e in [e for e in film if e.get("name") in ("width", "height", *(n for n, _ in _CROP))]:
        film.remove(e)
    ET.SubElement(film, "integer", name="width", value="$res")
    ET.SubElement(film, "integer", name="height", value="$res" if width == height else str(new_height))
    if any(name in given for name, _ in _CROP):
        x = min(resolution - 1, math.floor(crop["crop_offset_x"] * scale))
        y = min(new_height - 1, math.floor(crop["crop_offset_y"] * scale))
        w = crop["crop_width"] or width - crop["crop_offset_x"]
        h = crop["crop_height"] or height - crop["crop_offset_y"]
        for name, value in (("crop_offset_x", x), ("crop_offset_y", y),
                            ("crop_width", min(resolution - x, max(1, round(w * scale)))),
                            ("crop_height", min(new_height - y, max(1, round(h * scale))))):
            ET.SubElement(film, "integer", name=name, value=str(value))


def _default_film(resolution: int) -> ET.Element:
    film = ET.Element("film", type="hdrfilm")
    ET.SubElement(film, "integer", name="width", value="$res")
    ET.SubElement(film, "integer", name="height",
                  value=str(max(1, round(resolution * MITSUBA_FILM[1] / MITSUBA_FILM[0]))))
    return film


def default_sensor(bounds: tuple[tuple[float, ...], tuple[float, ...]] | None, resolution: int) -> ET.Element:
    """The camera Mitsuba gave a scene without a sensor until 3.0.0 (src/render/scene.cpp), for the bounding box
    `bounds` (min, max) or None (no shapes: at the origin), with Mitsuba's default sampler and a film of the
    run's resolution."""
    sensor = ET.Element("sensor", type="perspective")
    ET.SubElement(sensor, "float", name="fov", value=repr(DEFAULT_FOV))
    if bounds is not None:
        lo, hi = bounds
        extents = [b - a for a, b in zip(lo, hi)]
        distance = max(extents) / (2 * math.tan(math.radians(DEFAULT_FOV / 2)))
        ET.SubElement(sensor, "float", name="far_clip", value=repr(max(extents) * 5 + distance))
        ET.SubElement(sensor, "float", name="near_clip", value=repr(distance / 100))
        transform = ET.SubElement(sensor, "transform", name="to_world")
        center = [(a + b) / 2 for a, b in zip(lo, hi)]
        ET.SubElement(transform, "translate", x=repr(center[0]), y=repr(center[1]), z=repr(lo[2] - distance))
    sampler = ET.SubElement(sensor, "sampler", type="independent")
    ET.SubElement(sampler, "integer", name="sample_count", value="4")
    sensor.append(_default_film(resolution))
    return sensor


def _file_names(root: ET.Element) -> dict[int, str]:
    """The file names of `root`'s `filename` properties as written, by element."""
    return {id(e): e.get("value", "") for e in root.iter("string") if e.get("name") == "filename"}


def _missing_files(doc: LinedXml, root: ET.Element, written: dict[int, str]) -> None:
    """SceneXmlError for the first file a `filename` names that does not exist (after absolute_paths;
    `written`: the names as the file gives them)."""
    for e in root.iter("string"):
        value = e.get("value", "")
        if e.get("name") != "filename" or not value or "$" in value:
            continue
        # A pipe, a device or a folder: reading it would block, never end (/dev/zero) or fail in every engine.
        problem = ("no such file" if not Path(value).exists() else
                   "not a regular file" if not Path(value).is_file() else None)
        if problem:
            if id(e) in written:
                e.set("value", written[id(e)])
            raise _fail(doc, e, f"{problem} ({value})")


def _written(root: ET.Element) -> str:
    ET.indent(root)
    return ET.tostring(root, encoding="unicode")


def _source_lines(doc: LinedXml, root: ET.Element, text: str) -> list[int]:
    """Per line of `text` (root written), the line in the user's file of the element that starts there, or
    of its nearest ancestor read from the file (an element the copy added); 0 where none is known."""
    written = parse_lined(text, doc.path)
    parents = {id(c): p for p in root.iter() for c in p}
    result = [0] * (text.count("\n") + 2)
    for original, copy in zip(root.iter(), written.root.iter()):
        e, line = original, doc.line(original)
        while line is None and id(e) in parents:
            e = parents[id(e)]
            line = doc.line(e)
        result[written.line(copy)] = line or 0
    return result


def prepare_mitsuba_file(text: str, path: Path, resolution: int, bounds_of, lines: bool = True,
                         notes: list[str] | None = None) -> Prepared:
    """The copy of the Mitsuba 3 file `path` (its `text`) for a run at `resolution` (see the module docstring).
    `bounds_of(text)`: the bounding box (min, max) of the scene written as `text`, or None, asked only for a
    file without a sensor. SceneXmlError for what the copy cannot be made of, naming the file and line
    (`lines` False: `text` is a translation of the file, whose lines are not the file's; none are named).
    What the copy adds that changes the image (a camera) is a line in `notes`."""
    doc = parse_lined(text, path)
    if not lines:
        doc.lines.clear()
    root = doc.root
    read = list(root.iter())  # kept alive: `doc.lines` is keyed by id, which a freed element's successor reuses
    written = _file_names(root)
    absolute_paths(root, path, doc.lines)
    defaults = _defaults(doc)  # an included file's too
    _missing_files(doc, root, written)
    for film in root.iter("film"):
        _size_film(doc, film, defaults, resolution)
    sensors = list(root.iter("sensor"))
    for sensor in sensors:
        if not any(e.tag == "film" for e in sensor):
            sensor.append(_default_film(resolution))
    for e in [e for e in root if e.tag == "default" and e.get("name") == "res"]:
        root.remove(e)  # the file's own default would give another size
    root.insert(0, ET.Element("default", name="res", value=str(resolution)))
    if not sensors:
        # Appended last, so that the lines of the copy Mitsuba is asked about stay those of the copy.
        before = _written(root)
        try:
            bounds = bounds_of(before)
        except Exception as e:  # Mitsuba cannot load the file: its error, in the file's lines
            why = name_lines(str(e), "", str(path), _source_lines(doc, root, before))
            raise SceneXmlError(f"{path}: no <sensor>, and Mitsuba could not load it to place one: "
                                f"{why if type(e) is RuntimeError else f'{type(e).__name__}: {why}'}") from None
        root.append(default_sensor(bounds, resolution))
        if notes is not None:
            notes.append(f"{path}: no <sensor>: rendered from the camera Mitsuba gave such a file until 3.0.0 "
                         f"({DEFAULT_FOV:g} degree perspective, along +z from before the scene's bounding box); "
                         "Mitsuba 3 makes none")
    written = _written(root)
    lines = _source_lines(doc, root, written)
    del read
    return Prepared(written, lines)
