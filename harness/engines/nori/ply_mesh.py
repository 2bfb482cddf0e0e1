"""PLY meshes read with numpy, for writing them as OBJ files for Nori (baked_obj.py): binary little- or
big-endian or ASCII, vertices with x, y, z and optional nx, ny, nz, faces as vertex-index lists (polygons split
as fans: (0, 1, 2), (0, 2, 3), ..., as Mitsuba splits a quad)."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
          "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
          "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


class PlyError(ValueError):
    """A PLY file this reader cannot read, naming the file and what is wrong."""


def regular_file(path: Path) -> Path:
    """`path` if it is a regular file; PlyError otherwise, as a device or a pipe named as a mesh would be read
    without end (/dev/zero, a FIFO)."""
    path = Path(path)
    if path.exists() and not path.is_file():
        raise PlyError(f"{path}: not a regular file")
    return path


@dataclass
class PlyMesh:
    positions: np.ndarray        # (n, 3) float64
    normals: np.ndarray | None   # (n, 3) float64, or None when the file has none
    triangles: np.ndarray        # (m, 3) int64


def _header(data: bytes, path: Path) -> tuple[str, list[tuple[str, int, list[tuple]]], int]:
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise PlyError(f"{path}: not a PLY file")
    body = data.index(b"\n", end) + 1
    fmt, elements = "", []
    for line in data[:end].decode("ascii", "replace").splitlines()[1:]:
        words = line.split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property" and elements:
            if words[1] == "list":
                elements[-1][2].append((words[4], "list", _TYPES[words[2]], _TYPES[words[3]]))
            else:
                elements[-1][2].append((words[2], _TYPES[words[1]]))
    return fmt, elements, body


def read_ply(path: Path) -> PlyMesh:
    """The mesh in the PLY file at `path`; PlyError if it cannot be read."""
    data = regular_file(path).read_bytes()
    try:
        fmt, elements, offset = _header(data, path)
    except (KeyError, IndexError, ValueError) as e:
        raise PlyError(f"{path}: a PLY header this reader does not know ({e})") from None
    order = {"binary_little_endian": "<", "binary_big_endian": ">"}.get(fmt)
    ascii_words = data[offset:].split() if fmt == "ascii" else None
    at = 0
    vertices = faces = None
    for name, count, props in elements:
        if any(p[1] == "list" for p in props):
            if len(props) != 1:
                raise PlyError(f"{path}: element {name} mixes a list with other properties")
            _, _, count_type, index_type = props[0]
            rows = []
            if ascii_words is None and count:  # the usual file: every face has as many corners as the first
                n0 = int(np.frombuffer(data, order + count_type, 1, offset)[0])
                same = np.dtype([("n", order + count_type), ("i", order + index_type, (n0,))])
                if offset + count * same.itemsize <= len(data):
                    table = np.frombuffer(data, same, count, offset)
                    if np.all(table["n"] == n0):
                        rows, offset, count = table["i"].astype(np.int64), offset + count * same.itemsize, 0
            for _ in range(count):
                if ascii_words is not None:
                    n = int(ascii_words[at]); rows.append([int(w) for w in ascii_words[at + 1:at + 1 + n]])
                    at += 1 + n
                else:
                    n = int(np.frombuffer(data, order + count_type, 1, offset)[0])
                    offset += np.dtype(count_type).itemsize
                    rows.append(np.frombuffer(data, order + index_type, n, offset).tolist())
                    offset += n * np.dtype(index_type).itemsize
            if name == "face":
                faces = rows
        else:
            dtype = np.dtype([(p[0], (order or "<") + p[1]) for p in props])
            if ascii_words is not None:
                table = np.array(ascii_words[at:at + count * len(props)], float).reshape(count, len(props))
                at += count * len(props)
                columns = {p[0]: table[:, i] for i, p in enumerate(props)}
            else:
                table = np.frombuffer(data, dtype, count, offset)
                offset += count * dtype.itemsize
                columns = {p[0]: table[p[0]].astype(float) for p in props}
            if name == "vertex":
                vertices = columns
    if vertices is None or faces is None or not all(k in vertices for k in "xyz"):
        raise PlyError(f"{path}: no vertex positions or no faces")
    positions = np.stack([vertices[k] for k in "xyz"], axis=1)
    normals = np.stack([vertices[k] for k in ("nx", "ny", "nz")], axis=1) \
        if all(k in vertices for k in ("nx", "ny", "nz")) else None
    if isinstance(faces, np.ndarray):  # (m, k) corners: the fan (0, i, i + 1) of each
        triangles = np.stack([np.stack([faces[:, 0], faces[:, i], faces[:, i + 1]], axis=1)
                              for i in range(1, faces.shape[1] - 1)], axis=1).reshape(-1, 3) \
            if faces.shape[1] >= 3 else np.zeros((0, 3), np.int64)
    else:
        triangles = np.array([(f[0], f[i], f[i + 1]) for f in faces for i in range(1, len(f) - 1)], np.int64)
    if triangles.size == 0 or triangles.min() < 0 or triangles.max() >= len(positions):
        raise PlyError(f"{path}: no faces, or a face index outside the {len(positions)} vertices")
    return PlyMesh(positions, normals, triangles.reshape(-1, 3))
