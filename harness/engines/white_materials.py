"""A scene's materials made white for an integrator that reads none (ao): every surface an opaque diffuse one of
reflectance 1, lit on its back where its bsdf is twosided, as our renderer's ao sees it. An engine whose
integrator reads the materials (Mitsuba's) then renders the image of one that does not."""
from __future__ import annotations

import xml.etree.ElementTree as ET

from harness.engines.xml_lines import replace_keeping_lines

#: A shape's <ref name="..."> that names no material: its media.
MEDIUM_REFS = ("interior", "exterior")


def _white(bsdf_id: str | None) -> ET.Element:
    white = ET.Element("bsdf", type="diffuse")
    if bsdf_id is not None:
        white.set("id", bsdf_id)
    ET.SubElement(white, "rgb", name="reflectance", value="1")
    return white


def _whiten_below(top: ET.Element) -> None:
    """Every bsdf under `top` replaced by a white one; a twosided one keeps its sides, each made white.
    Iterative: a file may nest elements thousands deep."""
    stack = [top]
    while stack:
        parent = stack.pop()
        for child in list(parent):
            if child.tag == "bsdf" and child.get("type") != "twosided":
                replace_keeping_lines(parent, child, _white(child.get("id")))
            else:
                stack.append(child)


def _has_material(shape: ET.Element) -> bool:
    return any(e.tag == "bsdf" or (e.tag == "ref" and e.get("name") not in MEDIUM_REFS) for e in shape)


def white_materials(root: ET.Element) -> None:
    """`root` (its includes inlined) with white materials, in place; its lines kept (the file's line numbers
    stay those of the user's file). A shape without a material, which Mitsuba gives a diffuse one of
    reflectance 0.5, is given a white one."""
    for shape in root.iter("shape"):
        if shape.get("type") not in ("shapegroup", "instance") and not _has_material(shape):
            shape.append(_white(None))  # on the line of </shape>: no line moves
    _whiten_below(root)
