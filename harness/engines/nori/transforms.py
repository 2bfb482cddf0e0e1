"""<transform> in both dialects. Both compose their steps in file order, each applied after the previous, and
mean the same by each step (Nori's src/parser.cpp, Mitsuba's src/core/parser.cpp): `lookat` builds the same
frame (left = up x dir), `rotate` is right-handed in degrees (Nori normalises its axis, Mitsuba uses it as
given), `matrix` is row-major.
They differ only in spelling: Nori writes every vector as value="x, y, z" and a rotation axis as axis="...",
Mitsuba writes x/y/z attributes (or one `value`, which may be one number for all three)."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from typing import Callable

from harness.engines.nori.values import number_text, numbers, triple_text

Fail = Callable[[ET.Element, str], Exception]
_STEPS = ("translate", "scale", "rotate", "matrix", "lookat")
#: How far from length 1 a Mitsuba rotation axis may be (renderer/xml_props.cpp refuses the same).
UNIT_AXIS_TOLERANCE = 1e-5


def _triple(step: ET.Element, key: str, fail: Fail) -> list[float]:
    values = numbers(step.get(key, ""))
    if values is None or len(values) != 3:
        raise fail(step, f"{key} must be three finite numbers \"x, y, z\"")
    return values


def _xyz(step: ET.Element, default: float, fail: Fail) -> list[float]:
    """A Mitsuba vector step: `value` (one or three numbers) or x/y/z, each missing one `default`."""
    if "value" in step.attrib:
        values = numbers(step.get("value"))
        if values is None or len(values) not in (1, 3):
            raise fail(step, "value must be one or three finite numbers")
        return values * 3 if len(values) == 1 else values
    out = []
    for axis in "xyz":
        v = numbers(step.get(axis, str(default)))
        if v is None or len(v) != 1:
            raise fail(step, f"{axis} must be a finite number")
        out.append(v[0])
    return out


def _axis(axis: list[float], step: ET.Element, fail: Fail) -> list[float]:
    length = math.sqrt(sum(a * a for a in axis))
    if length == 0:
        raise fail(step, "the rotation axis is zero")
    return [a / length for a in axis]


def _matrix(step: ET.Element, fail: Fail) -> str:
    values = numbers(step.get("value", ""))
    if values is None or len(values) != 16:
        raise fail(step, "matrix needs 16 finite numbers, row by row")
    return " ".join(number_text(v) for v in values)


def nori_to_mitsuba(transform: ET.Element, fail: Fail) -> ET.Element:
    """Nori's <transform name="toWorld"> as Mitsuba's <transform name="to_world">."""
    out = ET.Element("transform", name="to_world")
    for step in transform:
        if step.tag == "translate":
            x, y, z = _triple(step, "value", fail)
            ET.SubElement(out, "translate", x=number_text(x), y=number_text(y), z=number_text(z))
        elif step.tag == "scale":
            x, y, z = _triple(step, "value", fail)
            ET.SubElement(out, "scale", x=number_text(x), y=number_text(y), z=number_text(z))
        elif step.tag == "rotate":
            x, y, z = _axis(_triple(step, "axis", fail), step, fail)
            angle = numbers(step.get("angle", ""))
            if angle is None or len(angle) != 1:
                raise fail(step, "angle must be one finite number (degrees)")
            ET.SubElement(out, "rotate", x=number_text(x), y=number_text(y), z=number_text(z),
                          angle=number_text(angle[0]))
        elif step.tag == "matrix":
            ET.SubElement(out, "matrix", value=_matrix(step, fail))
        elif step.tag == "lookat":
            ET.SubElement(out, "lookat", **{k: triple_text(_triple(step, k, fail))
                                            for k in ("origin", "target", "up")})
        else:
            raise fail(step, f"a transform holds only {', '.join(_STEPS)}")
    return out


def mitsuba_to_nori(transform: ET.Element, fail: Fail) -> ET.Element:
    """Mitsuba's <transform name="to_world"> as Nori's <transform name="toWorld">."""
    out = ET.Element("transform", name="toWorld")
    for step in transform:
        if step.tag == "translate":
            ET.SubElement(out, "translate", value=triple_text(_xyz(step, 0.0, fail)))
        elif step.tag == "scale":
            ET.SubElement(out, "scale", value=triple_text(_xyz(step, 1.0, fail)))
        elif step.tag == "rotate":
            angle = numbers(step.get("angle", ""))
            if angle is None or len(angle) != 1:
                raise fail(step, "angle must be one finite number (degrees)")
            axis = _xyz(step, 0.0, fail)
            if abs(math.sqrt(sum(a * a for a in axis)) - 1) > UNIT_AXIS_TOLERANCE:
                raise fail(step, "give a unit axis: Mitsuba 3 uses the axis as given (a shear when it is not "
                                 "unit), Nori normalises it")
            ET.SubElement(out, "rotate", axis=triple_text(axis), angle=number_text(angle[0]))
        elif step.tag == "matrix":
            ET.SubElement(out, "matrix", value=_matrix(step, fail))
        elif step.tag == "lookat":
            if not step.get("up"):
                raise fail(step, "Nori's lookat needs an up vector; write one (Mitsuba makes one up)")
            ET.SubElement(out, "lookat", **{k: triple_text(_triple(step, k, fail))
                                            for k in ("origin", "target", "up")})
        else:
            raise fail(step, f"Nori's transform holds only {', '.join(_STEPS)}")
    return out
