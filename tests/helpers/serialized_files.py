"""Mitsuba .serialized mesh files of our own (versions 3 and 4), for tests: Mitsuba's samples carry their
own licence, and a writer can also plant damage."""
from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass
class SerializedShape:
    positions: np.ndarray              # (n, 3)
    indices: np.ndarray                # (m, 3), counter-clockwise seen from the front
    normals: np.ndarray | None = None  # (n, 3)
    name: str = "shape"


def _payload(shape: SerializedShape, version: int) -> bytes:
    flags = 0x1000 | (0x1 if shape.normals is not None else 0)
    raw = struct.pack("<I", flags)
    if version >= 4:
        raw += shape.name.encode() + b"\0"
    raw += struct.pack("<QQ", len(shape.positions), len(shape.indices))
    raw += np.asarray(shape.positions, "<f4").tobytes()
    if shape.normals is not None:
        raw += np.asarray(shape.normals, "<f4").tobytes()
    return raw + np.asarray(shape.indices, "<u4").tobytes()


def write_serialized(path: Path, shapes: list[SerializedShape], version: int = 4) -> Path:
    """The shapes, each behind its header, then the table of offsets (u64 in version 4, u32 in 3) and the
    count, as Mitsuba writes them."""
    out, offsets = b"", []
    for shape in shapes:
        offsets.append(len(out))
        out += struct.pack("<HH", 0x041C, version) + zlib.compress(_payload(shape, version))
    out += struct.pack(f"<{len(offsets)}{'Q' if version >= 4 else 'I'}", *offsets)
    path.write_bytes(out + struct.pack("<I", len(shapes)))
    return path


def uv_sphere(rings: int = 6, segments: int = 10) -> SerializedShape:
    """A coarse unit sphere without normals: the vertex normals each engine computes are then compared too."""
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    positions = np.vstack([[0, 1, 0], ring, [0, -1, 0]])
    bottom, tris = len(positions) - 1, []
    for j in range(segments):
        k = (j + 1) % segments
        tris.append([0, 1 + k, 1 + j])
        tris.append([bottom, 1 + (rings - 2) * segments + j, 1 + (rings - 2) * segments + k])
        for i in range(rings - 2):
            a, b = 1 + i * segments + j, 1 + i * segments + k
            tris += [[a, b, b + segments], [a, b + segments, a + segments]]
    return SerializedShape(positions, np.array(tris), name="uv_sphere")


def pyramid() -> SerializedShape:
    """A square pyramid with normals of its own in the file (bent, so they show in the image)."""
    positions = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1], [0, 1.5, 0]], float)
    indices = np.array([[0, 4, 1], [1, 4, 2], [2, 4, 3], [3, 4, 0], [0, 1, 2], [0, 2, 3]])
    normals = positions - [0, 0.5, 0]
    return SerializedShape(positions, indices, normals / np.linalg.norm(normals, axis=1, keepdims=True), "pyramid")
