"""What float32 cannot represent: a transformed scene whose shapes float32 cannot place, so a break of an
invariance there is a limit of the number format, not a bug of the engine.

The check reads the rewritten scene itself (not the engine's error message), so an engine cannot excuse a
failure by refusing a scene. It knows the shapes whose size the file states exactly, the sphere, the disk
and the cylinder: float32 rounds a coordinate x to within spacing(x)/2, about |x| * 6e-8, so a point on a
sphere of radius R centred at largest coordinate C is off the surface by up to C * 6e-8. Below R = 1e-4 C
that is over 6e-4 R, which the nearly noiseless images of the suite resolve (its tile means move by about
that much). A disk's size is its smaller semi-axis (within a factor sqrt 2), a cylinder's the smaller of
its radius and length, as our renderer measures them (renderer/disk.cpp, renderer/cylinder.cpp).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from harness.closed_forms.plane_scene import NotAnalytic, shape_to_world, sphere_geometry

#: Smallest sphere radius over its centre's largest coordinate that float32 represents (see above).
MIN_RADIUS_TO_CENTRE = 1e-4


def _frame(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mitsuba's coordinate_system (Duff et al. 2017): s, t completing unit n to a right-handed frame."""
    sign = np.copysign(1.0, n[2])
    a = -1.0 / (sign + n[2])
    b = n[0] * n[1] * a
    return (np.array([1.0 + sign * n[0] ** 2 * a, sign * b, -sign * n[0]]),
            np.array([b, sign + n[1] ** 2 * a, -n[1]]))


def _point(shape: ET.Element, name: str, default) -> np.ndarray:
    el = next((c for c in shape if c.tag == "point" and c.get("name") == name), None)
    return np.array(default, dtype=float) if el is None else np.array(
        [float(v) for v in el.get("value").replace(",", " ").split()])


def disk_or_cylinder_geometry(shape: ET.Element) -> tuple[np.ndarray, float]:
    """A disk's or a cylinder's (centre, size) in world space, as renderer/disk_cylinder_loader.cpp builds them."""
    m = shape_to_world(shape)
    a, b = m[:3, :3], m[:3, 3]
    if shape.get("type") == "disk":
        u, v = a[:, 0], a[:, 1]
        return b, float(np.linalg.norm(np.cross(u, v)) / max(np.linalg.norm(u), np.linalg.norm(v)))
    p0, p1 = _point(shape, "p0", (0, 0, 0)), _point(shape, "p1", (0, 0, 1))
    radius_el = next((c for c in shape if c.tag == "float" and c.get("name") == "radius"), None)
    radius = 1.0 if radius_el is None else float(radius_el.get("value"))
    axis = p1 - p0
    length = float(np.linalg.norm(axis))
    s, t = _frame(axis / length)
    columns = a @ np.stack([s * radius, t * radius, axis], axis=1)
    base = a @ p0 + b
    return base + 0.5 * columns[:, 2], float(np.min(np.linalg.norm(columns, axis=0)))


def float32_limit(scene: Path) -> str | None:
    """Why float32 cannot represent `scene` (a rewritten scene, no $parameters in its shapes), or None."""
    for shape in ET.parse(scene).getroot().iter("shape"):
        kind = shape.get("type")
        if kind not in ("sphere", "disk", "cylinder"):
            continue
        try:
            centre, size = sphere_geometry(shape) if kind == "sphere" else disk_or_cylinder_geometry(shape)
        except (NotAnalytic, ValueError, ZeroDivisionError):
            continue  # an ellipsoid, a parameter or a degenerate shape: the engine's own checks apply
        largest = float(np.max(np.abs(centre)))
        if size < MIN_RADIUS_TO_CENTRE * largest:
            spacing = float(np.spacing(np.float32(largest)))
            measure = "radius" if kind == "sphere" else "size"
            return (f"not representable in float32: a {kind} of {measure} {size:.3g} centred at largest coordinate "
                    f"{largest:.4g}, where float32's spacing is {spacing:.2g} ({spacing / size:.2g} of the {measure}); "
                    f"a {kind} needs a {measure} of at least {MIN_RADIUS_TO_CENTRE:g} times that coordinate, so this "
                    f"starts once the centre is {size / MIN_RADIUS_TO_CENTRE:.3g} ({1 / MIN_RADIUS_TO_CENTRE:g} "
                    f"{'radii' if kind == 'sphere' else 'sizes'}) from the origin along an axis")
    return None
