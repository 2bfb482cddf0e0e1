"""Mitsuba's flat shapes as OBJ files, Nori's only geometry: `rectangle` is [-1, 1]^2 in z = 0 facing +z and
`cube` is [-1, 1]^3 facing outwards (Mitsuba's src/shapes/rectangle.cpp, cube.cpp). Without `vn` lines Nori
shades them with their face normals, which is what Mitsuba's flat shapes have."""
from __future__ import annotations

_RECTANGLE = """# Mitsuba's rectangle: [-1, 1]^2 in z = 0, normal +z
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
f 1 2 3
f 1 3 4
"""

# The cube's corners, index = 1 + 4 (x > 0) + 2 (y > 0) + (z > 0); each face counter-clockwise seen from outside.
_CUBE_FACES = ((1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4))


def _cube() -> str:
    lines = ["# Mitsuba's cube: [-1, 1]^3, normals outwards"]
    lines += [f"v {x} {y} {z}" for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    for a, b, c, d in _CUBE_FACES:
        lines += [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    return "\n".join(lines) + "\n"


#: OBJ text of each shape type that has one.
OBJ_TEXT = {"rectangle": _RECTANGLE, "cube": _cube()}

