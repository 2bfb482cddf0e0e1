"""A Mitsuba mesh written as an OBJ file in world space, for Nori: its to_world applied to the positions, and
the normals Mitsuba shades it with written as `vn` (the file's own, by the inverse transpose; else, unless
face_normals, the angle-weighted normals Mitsuba computes from the world-space triangles, as
renderer/mesh.cpp does). Without `vn` Nori uses face normals, as Mitsuba does with face_normals."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np

from harness.engines.nori.ply_mesh import PlyMesh
from harness.engines.nori.values import numbers


def _vector(step: ET.Element, default: float) -> np.ndarray:
    if "value" in step.attrib:
        v = numbers(step.get("value")) or [default]
        return np.array(v * 3 if len(v) == 1 else v, float)
    return np.array([float(step.get(a, default)) for a in "xyz"])


def _vec(text: str) -> np.ndarray:
    return np.array(numbers(text), float)


def step_matrix(step: ET.Element) -> np.ndarray:
    """One Mitsuba transform step as a 4x4 matrix (src/core/parser.cpp, Transform4f)."""
    m = np.eye(4)
    if step.tag == "translate":
        m[:3, 3] = _vector(step, 0.0)
    elif step.tag == "scale":
        m[:3, :3] = np.diag(_vector(step, 1.0))
    elif step.tag == "rotate":
        x, y, z = _vector(step, 0.0)  # as given: Mitsuba does not normalise it (a non-unit axis shears)
        a = math.radians(float(step.get("angle")))
        c, s = math.cos(a), math.sin(a)
        k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
        m[:3, :3] = c * np.eye(3) + s * k + (1 - c) * np.outer([x, y, z], [x, y, z])
    elif step.tag == "matrix":
        m = np.array(numbers(step.get("value")), float).reshape(4, 4)
    elif step.tag == "lookat":
        origin, target, up = _vec(step.get("origin")), _vec(step.get("target")), _vec(step.get("up"))
        d = (target - origin) / np.linalg.norm(target - origin)
        left = np.cross(up, d)
        left /= np.linalg.norm(left)
        m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = left, np.cross(d, left), d, origin
    return m


def transform_matrix(transform: ET.Element | None) -> np.ndarray:
    """A <transform>'s steps composed in file order, each applied after the previous."""
    m = np.eye(4)
    for step in (transform if transform is not None else ()):
        m = step_matrix(step) @ m
    return m


def _vertex_normals(p: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Each vertex's normal: the sum of its triangles' unit normals weighted by their angle there."""
    v = p[tri]                                            # (m, 3 corners, 3)
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
    total = np.zeros_like(p)
    for j in range(3):
        d0, d1 = v[:, (j + 1) % 3] - v[:, j], v[:, (j + 2) % 3] - v[:, j]
        l0, l1 = np.linalg.norm(d0, axis=1), np.linalg.norm(d1, axis=1)
        ok = (l0 > 0) & (l1 > 0)
        cos = np.clip(np.einsum("ij,ij->i", d0, d1) / np.where(ok, l0 * l1, 1), -1, 1)
        np.add.at(total, tri[:, j], n * (np.arccos(cos) * ok)[:, None])
    length = np.linalg.norm(total, axis=1, keepdims=True)
    return np.where(length > 0, total / np.where(length > 0, length, 1), [0.0, 0.0, 1.0])


def world_obj(mesh: PlyMesh, to_world: ET.Element | None, face_normals: bool) -> str:
    """The OBJ text of `mesh` placed by `to_world`, with the normals Mitsuba would shade it with."""
    m = transform_matrix(to_world)
    p = mesh.positions @ m[:3, :3].T + m[:3, 3]
    normals = None
    if not face_normals:
        if mesh.normals is not None:
            normals = mesh.normals @ np.linalg.inv(m[:3, :3])  # rows times the inverse transpose
            normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        else:
            normals = _vertex_normals(p, mesh.triangles)
    lines = ["# written by mcval for Nori: world space" + ("" if normals is None else ", with Mitsuba's normals")]
    lines += [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in p]
    if normals is None:
        lines += [f"f {a} {b} {c}" for a, b, c in mesh.triangles + 1]
    else:
        lines += [f"vn {x:.9g} {y:.9g} {z:.9g}" for x, y, z in normals]
        lines += [f"f {a}//{a} {b}//{b} {c}//{c}" for a, b, c in mesh.triangles + 1]
    return "\n".join(lines) + "\n"
