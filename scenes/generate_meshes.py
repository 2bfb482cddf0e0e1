#!/usr/bin/env python3
"""Generate the meshes the scene files use (numpy only, nothing downloaded).

    python scenes/generate_meshes.py [--out scenes/meshes] [--force]

Writes binary little-endian PLY files, all triangles, wound counter-clockwise
seen from outside (so the geometric normal cross(v1 - v0, v2 - v0) points
outward):

* ``sphere.ply``           UV sphere, radius 1, centre 0, 64 x 32 segments,
                           per-vertex normals (= position), one vertex per pole
                           with triangle fans (no degenerate triangles).
* ``sphere_nonormals.ply`` the same geometry without normals.
* ``highpoly.ply``         a bumpy blob (a sphere displaced radially by a smooth
                           sum of sinusoids), ~530k triangles, no normals.
* ``slats.ply``            a row of thin boxes with narrow gaps (crevices),
                           flat faces (4 vertices per face), no normals.

A file is rewritten only when it is missing or was written by another version
of this script or with other parameters (the header carries a stamp); use
``--force`` to rewrite everything. Each file is written to a temporary file in
the output folder, then moved into place with ``os.replace``.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# Bump when the geometry of any mesh changes, so stale files get rewritten.
GENERATOR_VERSION = 1

DEFAULT_OUT = Path(__file__).resolve().parent / "meshes"


# --------------------------------------------------------------------------
# PLY writing
# --------------------------------------------------------------------------

def _stamp(name: str, params: dict) -> str:
    text = f"{name} v{GENERATOR_VERSION} " + " ".join(f"{k}={params[k]}" for k in sorted(params))
    return "mcval generate_meshes " + hashlib.sha1(text.encode()).hexdigest()[:16]


def _ply_bytes(positions: np.ndarray, faces: np.ndarray, normals: np.ndarray | None,
               comments: list[str]) -> bytes:
    positions = np.ascontiguousarray(positions, dtype="<f4")
    faces = np.asarray(faces)
    assert positions.ndim == 2 and positions.shape[1] == 3
    assert faces.ndim == 2 and faces.shape[1] == 3
    assert faces.min() >= 0 and faces.max() < len(positions)
    header = ["ply", "format binary_little_endian 1.0"]
    header += [f"comment {c}" for c in comments]
    header += [f"element vertex {len(positions)}",
               "property float x", "property float y", "property float z"]
    if normals is not None:
        header += ["property float nx", "property float ny", "property float nz"]
    header += [f"element face {len(faces)}",
               "property list uchar int vertex_indices", "end_header"]
    head = ("\n".join(header) + "\n").encode("ascii")

    if normals is not None:
        vert = np.concatenate([positions, np.asarray(normals, dtype="<f4")], axis=1)
    else:
        vert = positions
    face = np.empty(len(faces), dtype=np.dtype([("n", "u1"), ("i", "<i4", (3,))]))
    face["n"] = 3
    face["i"] = faces
    return head + np.ascontiguousarray(vert, dtype="<f4").tobytes() + face.tobytes()


def _write_atomic(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o644)           # mkstemp makes 0600; meshes are ordinary files
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise


def _is_up_to_date(path: Path, stamp: str) -> bool:
    try:
        with open(path, "rb") as f:
            head = f.read(1024)
    except OSError:
        return False
    end = head.find(b"end_header\n")
    return end >= 0 and f"comment {stamp}\n".encode() in head[:end]


# --------------------------------------------------------------------------
# Geometry
# --------------------------------------------------------------------------

def _check_outward(positions: np.ndarray, faces: np.ndarray, centre=(0.0, 0.0, 0.0)) -> None:
    """Every triangle non-degenerate, its normal pointing away from `centre`."""
    p = positions.astype(np.float64)
    v0, v1, v2 = p[faces[:, 0]], p[faces[:, 1]], p[faces[:, 2]]
    n = np.cross(v1 - v0, v2 - v0)
    area2 = np.linalg.norm(n, axis=1)
    assert area2.min() > 0, "degenerate triangle"
    c = (v0 + v1 + v2) / 3 - np.asarray(centre)
    assert (np.einsum("ij,ij->i", n, c) > 0).all(), "inward-facing triangle"


def uv_sphere(n_lon: int = 64, n_lat: int = 32):
    """Unit UV sphere around +y: one vertex per pole, n_lat - 1 rings of n_lon.

    Vertex 0 is the north pole (0, 1, 0), the last vertex the south pole.
    Returns (positions float64 (V, 3), faces int32 (F, 3)), F = 2 n_lon (n_lat - 1).
    """
    theta = np.pi * np.arange(1, n_lat) / n_lat             # polar angle of the rings
    phi = 2 * np.pi * np.arange(n_lon) / n_lon              # azimuth
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    ring = np.stack(np.broadcast_arrays(st * np.cos(phi), ct, -st * np.sin(phi)), axis=-1)
    positions = np.concatenate([[[0.0, 1.0, 0.0]], ring.reshape(-1, 3), [[0.0, -1.0, 0.0]]])

    n_rings = n_lat - 1
    south = 1 + n_rings * n_lon
    j = np.arange(n_lon)
    jn = (j + 1) % n_lon

    def idx(r, k):
        return 1 + r * n_lon + k

    faces = [np.stack([np.zeros_like(j), idx(0, j), idx(0, jn)], axis=1)]      # north fan
    r = np.arange(n_rings - 1)[:, None]
    a, b = idx(r, j), idx(r, jn)                  # upper ring
    c, d = idx(r + 1, j), idx(r + 1, jn)          # lower ring
    faces.append(np.stack([a, c, d], axis=-1).reshape(-1, 3))
    faces.append(np.stack([a, d, b], axis=-1).reshape(-1, 3))
    faces.append(np.stack([np.full_like(j, south), idx(n_rings - 1, jn), idx(n_rings - 1, j)], axis=1))
    faces = np.concatenate(faces).astype(np.int32)
    return positions, faces


def cube_sphere(n: int):
    """Unit sphere from a cube whose faces are n x n grids (equal-angle mapping).

    Shared vertices (6 n^2 + 2), 12 n^2 triangles wound outward.
    """
    t = np.tan(np.pi / 4 * (2 * np.arange(n + 1) / n - 1))      # equal-angle grid on [-1, 1]
    keys, quads = [], []
    base = 0
    # Each cube face: fixed axis `ax` at sign `s`, grid over the two other axes.
    for ax in range(3):
        u_ax, v_ax = [a for a in range(3) if a != ax]
        for s in (-1, 1):
            iu, iv = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
            key = np.empty((n + 1, n + 1, 3), dtype=np.int64)
            key[..., ax] = 0 if s < 0 else n
            key[..., u_ax], key[..., v_ax] = iu, iv
            keys.append(key.reshape(-1, 3))
            k = base + iu[:-1, :-1] * (n + 1) + iv[:-1, :-1]
            quads.append(np.stack([k, k + n + 1, k + n + 2, k + 1], axis=-1).reshape(-1, 4))
            base += (n + 1) ** 2
    keys = np.concatenate(keys)
    quads = np.concatenate(quads)
    uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    quads = inverse[quads]
    cube = t[uniq]                                   # positions on the cube [-1, 1]^3
    positions = cube / np.linalg.norm(cube, axis=1, keepdims=True)
    # Split each quad along the shorter diagonal.
    q = positions[quads]
    diag02 = np.linalg.norm(q[:, 0] - q[:, 2], axis=1)
    diag13 = np.linalg.norm(q[:, 1] - q[:, 3], axis=1)
    use02 = (diag02 <= diag13)[:, None]
    t1 = np.where(use02, quads[:, [0, 1, 2]], quads[:, [0, 1, 3]])
    t2 = np.where(use02, quads[:, [0, 2, 3]], quads[:, [1, 2, 3]])
    faces = np.concatenate([t1, t2])
    # Orient every triangle outward (the grid's handedness differs per face).
    p = positions
    nrm = np.cross(p[faces[:, 1]] - p[faces[:, 0]], p[faces[:, 2]] - p[faces[:, 0]])
    inward = np.einsum("ij,ij->i", nrm, p[faces].sum(axis=1)) < 0
    faces[inward] = faces[inward][:, ::-1]
    return positions, faces.astype(np.int32)


def blob_radius(d: np.ndarray) -> np.ndarray:
    """Radius of the bumpy blob along unit directions d (N, 3): smooth, in [0.7, 1.3]."""
    x, y, z = d[:, 0], d[:, 1], d[:, 2]
    r = 1.0
    r = r + 0.12 * np.sin(2.0 * y + 0.4) * np.cos(1.5 * x)          # broad lobes
    r = r + 0.07 * np.sin(5.0 * x + 1.0) * np.sin(4.0 * z + 0.3)    # bumps
    r = r + 0.05 * np.cos(6.0 * y - 3.0 * z + 0.7)                  # diagonal ridges
    r = r + 0.012 * np.sin(31.0 * x + 2.0) * np.sin(29.0 * y) * np.sin(27.0 * z + 1.0)  # fine detail
    return r


def highpoly(n: int = 210):
    d, faces = cube_sphere(n)
    r = blob_radius(d)
    positions = d * r[:, None]
    positions[:, 1] *= 1.15                                  # a little taller than wide
    return positions, faces


def slats(count: int = 10, thickness: float = 0.12, gap: float = 0.08,
          height: float = 1.0, depth: float = 2.0):
    """`count` boxes along x, standing on y = 0, centred on x = 0 and z = 0.

    Flat faces: 4 own vertices per face, so computed vertex normals are flat.
    """
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    # Faces of the unit cube as corner quads wound counter-clockwise from outside.
    quads = np.array([[0, 1, 3, 2], [4, 6, 7, 5],       # -x, +x
                      [0, 4, 5, 1], [2, 3, 7, 6],       # -y, +y
                      [0, 2, 6, 4], [1, 5, 7, 3]])      # -z, +z
    pitch = thickness + gap
    width = count * thickness + (count - 1) * gap
    positions, faces = [], []
    for i in range(count):
        lo = np.array([-width / 2 + i * pitch, 0.0, -depth / 2])
        size = np.array([thickness, height, depth])
        box = lo + corners * size
        for q in quads:
            base = len(positions) * 4
            positions.append(box[q])
            faces += [[base, base + 1, base + 2], [base, base + 2, base + 3]]
    positions = np.concatenate(positions)
    faces = np.array(faces, dtype=np.int32)
    return positions, faces


# --------------------------------------------------------------------------
# The meshes
# --------------------------------------------------------------------------

def _sphere(normals: bool):
    def build():
        p, f = uv_sphere(64, 32)
        _check_outward(p, f)
        return p, f, (p if normals else None)
    return build


def _highpoly():
    p, f = highpoly(210)
    _check_outward(p, f)
    return p, f, None


def _slats():
    p, f = slats()
    return p, f, None


# name -> (builder, parameters recorded in the stamp, description)
MESHES = {
    "sphere.ply": (_sphere(True), {"n_lon": 64, "n_lat": 32, "normals": 1},
                   "UV sphere r=1 at origin, 64x32, pole fans, vertex normals"),
    "sphere_nonormals.ply": (_sphere(False), {"n_lon": 64, "n_lat": 32, "normals": 0},
                             "UV sphere r=1 at origin, 64x32, pole fans, no normals"),
    "highpoly.ply": (_highpoly, {"n": 210},
                     "bumpy blob, cube-sphere 6x210x210 quads displaced radially"),
    "slats.ply": (_slats, {"count": 10, "thickness": 0.12, "gap": 0.08, "height": 1.0, "depth": 2.0},
                  "10 slats 0.12 thick, gaps 0.08, 1 high, 2 deep, on y=0"),
}


def generate(out: Path, force: bool = False, verbose: bool = False) -> list[Path]:
    """Write the meshes that are missing or stale into `out`; return the paths written."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, (build, params, description) in MESHES.items():
        path = out / name
        stamp = _stamp(name, params)
        if not force and _is_up_to_date(path, stamp):
            continue
        t0 = time.perf_counter()
        positions, faces, normals = build()
        _write_atomic(path, _ply_bytes(positions, faces, normals, [stamp, description]))
        written.append(path)
        if verbose:
            print(f"wrote {path} ({len(faces)} triangles, {path.stat().st_size / 1e6:.1f} MB, "
                  f"{time.perf_counter() - t0:.2f} s)")
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT,
                        help="output folder (default: scenes/meshes next to this script)")
    parser.add_argument("--force", action="store_true", help="rewrite every mesh")
    parser.add_argument("-q", "--quiet", action="store_true", help="print nothing")
    args = parser.parse_args(argv)
    generate(args.out, force=args.force, verbose=not args.quiet)
    return 0


if __name__ == "__main__":
    sys.exit(main())
