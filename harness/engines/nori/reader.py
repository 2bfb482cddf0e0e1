"""Reading Nori's elements: their properties checked against what Nori's class reads, and their numbers
checked where they are read; a mistake is one NoriSceneError naming the file, the element's line and why."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

from harness.engines.nori.lined_xml import LinedXml
from harness.engines.nori.transforms import nori_to_mitsuba as transform_to_mitsuba
from harness.engines.nori.values import numbers, triple_text

#: Nori's property tags and Mitsuba's name for each (a <color> is RGB).
PROPERTY_TAGS = {"float": "float", "integer": "integer", "boolean": "boolean", "string": "string",
                 "point": "point", "vector": "vector", "color": "rgb", "transform": "transform"}


class Reader:
    """One Nori file's elements read with their checks; `fail` makes the error naming an element's line."""

    def __init__(self, doc: LinedXml) -> None:
        self.doc = doc
        self.fail = doc.fail
        #: What was read past, one line each: properties no Nori class reads (Nori ignores them too).
        self.notes: list[str] = []

    def props(self, e: ET.Element, allowed: dict[str, str], objects: tuple[str, ...] = ()) -> dict[str, ET.Element]:
        """`e`'s properties by name, each checked against `allowed` (name -> Nori tag); its object children
        (tags in `objects`) are left to the caller."""
        found = {}
        for child in e:
            if child.tag in objects:
                continue
            name = child.get("name", "")
            if child.tag not in PROPERTY_TAGS:
                raise self.fail(child, f"<{e.tag} type=\"{e.get('type')}\"> holds no <{child.tag}> here")
            known = ", ".join(f"{t} {n}" for n, t in allowed.items()) or "none"
            if name not in allowed:  # Nori's classes ask for what they read; the rest goes unread
                self.notes.append(f"{self.doc.where(child)}: <{child.tag} name=\"{name}\">: ignored, as Nori ignores "
                                  f"it: its {e.get('type')} {e.tag} reads {known}")
                continue
            if allowed[name] != child.tag:
                raise self.fail(child, f"Nori's {e.get('type')} {e.tag} reads {name!r} as a <{allowed[name]}>, not a "
                                       f"<{child.tag}>")
            if name in found:
                raise self.fail(child, f"{name!r} is given twice")
            found[name] = child
        return found

    def number(self, e: ET.Element | None, default: float, low: float = -math.inf) -> float:
        if e is None:
            return float(default)
        values = numbers(e.get("value", ""))
        if values is None or len(values) != 1 or values[0] < low:
            raise self.fail(e, f"expected one finite number{f' of at least {low:g}' if low > -math.inf else ''}")
        return values[0]

    def color(self, e: ET.Element | None, default: float) -> list[float]:
        if e is None:
            return [default] * 3
        values = numbers(e.get("value", ""))
        if values is None or len(values) != 3 or min(values) < 0:
            raise self.fail(e, "expected three finite numbers >= 0 \"r, g, b\"")
        return values

    def triple(self, e: ET.Element) -> list[float]:
        values = numbers(e.get("value", ""))
        if values is None or len(values) != 3:
            raise self.fail(e, "expected three finite numbers \"x, y, z\"")
        return values

    def transform(self, e: ET.Element | None) -> list[ET.Element]:
        return [] if e is None else [transform_to_mitsuba(e, self.fail)]


def rgb(name: str, values: list[float]) -> ET.Element:
    return ET.Element("rgb", name=name, value=triple_text(values))


def obj_has_normals(filename: str, scene: Path) -> bool | None:
    """Whether the OBJ file has `vn` lines (None if it cannot be read, or is not a regular file: the engines then
    say so)."""
    path = Path(filename) if Path(filename).is_absolute() else scene.parent / filename
    if not path.is_file():
        return None
    try:
        with open(path, errors="replace") as f:
            return any(line.startswith("vn ") for line in f)
    except OSError:
        return None
