"""XML read with the line of every element, which ElementTree does not keep: Nori's scene files are read with
expat, so that a refusal names the line of the element it refuses."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat


#: Elements nested deeper than this are refused: Mitsuba's and Nori's scenes nest a few levels (a BSDF in a
#: wrapper in a shape), and ElementTree writes and indents a tree recursively.
MAX_DEPTH = 100


class SceneXmlError(ValueError):
    """A scene file that cannot be read or prepared, as one line: "FILE:LINE: <element>: why"."""


class NoriSceneError(SceneXmlError):
    """A Nori scene file that cannot be translated, as one line: "FILE:LINE: <element>: why"."""


@dataclass
class LinedXml:
    """A parsed file: its root and the line each element starts on (keyed by the element itself)."""

    path: Path
    root: ET.Element
    lines: dict[int, int] = field(default_factory=dict)

    def line(self, e: ET.Element) -> int | None:
        """`e`'s line, or None for an element that was not read from this file (one an <include> brought)."""
        return self.lines.get(id(e))

    def where(self, e: ET.Element) -> str:
        """"FILE:LINE" of `e` ("FILE" when its line is unknown)."""
        line = self.line(e)
        return f"{self.path}{'' if line is None else f':{line}'}"

    def fail(self, e: ET.Element, why: str) -> NoriSceneError:
        """The error naming the file, `e`'s line, `e` as it is written (tag and attributes) and `why`."""
        attrs = "".join(f' {k}="{v}"' for k, v in e.attrib.items())
        return NoriSceneError(f"{self.where(e)}: <{e.tag}{attrs}>: {why}")


def parse_lined(text: str, path: Path) -> LinedXml:
    """`text` (the file at `path`) parsed; NoriSceneError with the line of the first syntax error, or of the
    first element nested deeper than MAX_DEPTH."""
    builder = ET.TreeBuilder()
    parser = expat.ParserCreate()
    lines: dict[int, int] = {}
    depth = 0

    def start(tag: str, attrs: dict[str, str]) -> None:
        nonlocal depth
        depth += 1
        if depth > MAX_DEPTH:
            raise NoriSceneError(f"{path}:{parser.CurrentLineNumber}: <{tag[:40]}>: elements nested more than "
                                 f"{MAX_DEPTH} deep (no scene nests so far)")
        lines[id(builder.start(tag, attrs))] = parser.CurrentLineNumber

    def end(tag: str) -> None:
        nonlocal depth
        depth -= 1
        builder.end(tag)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = builder.data
    try:
        parser.Parse(text, True)
    except expat.ExpatError as e:
        raise NoriSceneError(f"{path}:{e.lineno}: not valid XML: {expat.ErrorString(e.code)}") from None
    return LinedXml(path, builder.close(), lines)
