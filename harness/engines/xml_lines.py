"""Editing a scene's element tree without moving its lines: an engine's error then names the line of the file
it was given (the prepared copy of a --scene file, whose lines map to the user's: harness/images/scene_copy.py)."""
from __future__ import annotations

import xml.etree.ElementTree as ET


def remove_keeping_lines(parent: ET.Element, e: ET.Element) -> None:
    """`e` removed from `parent`, the lines it took left blank (in place)."""
    tail, e.tail = e.tail, None
    newlines = ET.tostring(e, encoding="unicode").count("\n") + (tail or "").count("\n")
    index = list(parent).index(e)
    parent.remove(e)
    if index > 0:
        parent[index - 1].tail = (parent[index - 1].tail or "") + "\n" * newlines
    else:
        parent.text = (parent.text or "") + "\n" * newlines


def replace_keeping_lines(parent: ET.Element, old: ET.Element, new: ET.Element) -> None:
    """`old` replaced by `new` (written on one line) in `parent`, the lines `old` took left blank (in place)."""
    tail, old.tail = old.tail, None
    newlines = ET.tostring(old, encoding="unicode").count("\n") + (tail or "").count("\n")
    parent[list(parent).index(old)] = new
    new.tail = "\n" * newlines
