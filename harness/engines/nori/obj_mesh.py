"""OBJ meshes read as Mitsuba reads them, for writing them again in world space for Nori (baked_obj.py): one
vertex per distinct corner (position, texture and normal index together), faces split as fans
(0, 1, 2), (0, 2, 3), ...; `vn` normals are not kept (a mesh baked for Nori has none of its own to keep)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from harness.engines.nori.ply_mesh import PlyError, PlyMesh, regular_file


def read_obj(path: Path) -> PlyMesh:
    """The triangles of the OBJ file at `path` over its distinct corners; PlyError naming the file and line."""
    positions: list[list[float]] = []
    corners: dict[tuple[int, ...], int] = {}
    triangles: list[tuple[int, int, int]] = []
    with open(regular_file(path), errors="replace") as f:
        for number, line in enumerate(f, 1):
            words = line.split()
            try:
                if words and words[0] == "v":
                    positions.append([float(w) for w in words[1:4]])
                elif words and words[0] == "f":
                    face = []
                    for token in words[1:]:
                        fields = [int(x) if x else 0 for x in token.split("/")]
                        if fields[0] < 0:  # relative to the positions read so far
                            fields[0] += len(positions) + 1
                        if not 1 <= fields[0] <= len(positions):
                            raise ValueError(f"vertex {fields[0]} of {len(positions)}")
                        face.append(corners.setdefault(tuple(fields), len(corners)))
                    triangles += [(face[0], face[i], face[i + 1]) for i in range(1, len(face) - 1)]
            except ValueError as e:
                raise PlyError(f"{path}:{number}: not an OBJ line this reader knows ({e})") from None
    if not triangles:
        raise PlyError(f"{path}: no faces")
    corner_positions = np.array([positions[key[0] - 1] for key in corners], float)
    return PlyMesh(corner_positions, None, np.array(triangles, np.int64))
