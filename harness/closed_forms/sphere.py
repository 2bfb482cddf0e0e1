"""A sphere of radius R resting on a diffuse floor (tangent at one point): its exact geometry and the two
visibility terms the closed forms need.

Unoccluded cosine-weighted fraction of the hemisphere, the only thing ao integrates (L = L_env * V):
  - floor point at distance D from the centre: the sphere, wholly above the horizon, subtends the
    cosine-weighted form factor (R/D)^2 cos(theta) with cos(theta) = R/D (the centre is R above the floor),
    so V = 1 - (R/D)^3;
  - sphere point with normal n: the sphere cannot occlude itself (convex) and the floor cuts the cosine lobe
    at the horizon, so V = (1 + n.up) / 2 (up = the floor's normal).
The floor is finite: from a sphere point (height <= 2R) it misses the directions within 2R/L of the
horizon (L the floor's half-size). MIN_FLOOR_RATIO keeps that below 1.3e-4 of L_env anywhere on the
sphere ((2/pi) * 2R/L), under what a 128x128 image can detect.

Point lights (simple): a floor point is lit unless the segment to the light crosses the sphere; a sphere
point is lit iff n.l > 0 (the segment to a light above the floor stays above it, so the floor never shadows).
"""
from __future__ import annotations

import numpy as np

from harness.closed_forms.plane_scene import NotAnalytic, PlaneScene
from harness.closed_forms.vectors import dot, norm, sub

#: The floor's half-size over the sphere's radius below which the finite floor could show.
MIN_FLOOR_RATIO = 1e4


def floor_frame(scene: PlaneScene) -> tuple[np.ndarray, np.ndarray, float]:
    """The floor's unit normal, a point on it, and its smaller half-size."""
    normal = np.linalg.inv(scene.plane[:3, :3]).T @ np.array([0.0, 0.0, 1.0])
    half = min(np.linalg.norm(scene.plane[:3, 0]), np.linalg.norm(scene.plane[:3, 1]))
    return normal / np.linalg.norm(normal), scene.plane[:3, 3], float(half)


def check_resting(scene: PlaneScene) -> None:
    """NotAnalytic unless the sphere rests on the floor's front side, inside it, the floor is large enough
    and every point light is above the floor and outside the sphere."""
    s = scene.sphere
    up, origin, half = floor_frame(scene)
    height = float((s.center - origin) @ up)
    if abs(height - s.radius) > 1e-9 * s.radius:
        raise NotAnalytic(f"the sphere's centre is {height:g} above the floor, not its radius {s.radius:g}")
    contact = s.center - s.radius * up
    uv = np.linalg.inv(scene.plane)[:3, :3] @ contact + np.linalg.inv(scene.plane)[:3, 3]
    if np.any(np.abs(uv[:2]) > 1 - MIN_FLOOR_RATIO * s.radius / half) or half < MIN_FLOOR_RATIO * s.radius:
        raise NotAnalytic(f"the floor must reach {MIN_FLOOR_RATIO:g} radii from the contact point")
    for position, _ in scene.lights:
        if (position - origin) @ up <= 0 or np.linalg.norm(position - s.center) <= s.radius:
            raise NotAnalytic("a point light below the floor or inside the sphere")


def hit_sphere(scene: PlaneScene, origin: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Nearest positive distance along unit directions d (..., 3) to the sphere, inf on a miss."""
    return nearest_hit(scene, d @ (origin - scene.sphere.center), origin)


def nearest_hit(scene: PlaneScene, b: np.ndarray, origin: np.ndarray | None = None) -> np.ndarray:
    """hit_sphere from the camera (or `origin`), given b = d . (origin - centre) per direction."""
    s = scene.sphere
    oc = (scene.origin if origin is None else origin) - s.center
    disc = np.asarray(b * b - (oc @ oc - s.radius**2))
    rows = np.flatnonzero(disc > 0)  # the rays' lines that meet the sphere (the rest of the work is on these)
    b, root = -np.ravel(b)[rows], np.sqrt(disc.ravel()[rows])
    near, far = b - root, b + root
    t = np.where(near > 0, near, far)
    ahead = t > 0
    out = np.full(disc.shape, np.inf)
    out.reshape(-1)[rows[ahead]] = t[ahead]
    return out


def segment_crosses_sphere(scene: PlaneScene, p: np.ndarray, light: np.ndarray) -> np.ndarray:
    """Whether the open segment from each point of p (..., 3) to `light` passes through the sphere."""
    s = scene.sphere
    d = sub(light, p)
    length = norm(d)
    d = [x / length for x in d]
    oc = sub(p, s.center)
    b = dot(d, oc)
    disc = b * b - (dot(oc, oc) - s.radius**2)
    root = np.sqrt(np.maximum(disc, 0.0))
    # The chord [-b - root, -b + root] overlaps (0, length): the sphere lies between point and light.
    return (disc > 0) & (-b + root > 0) & (-b - root < length)


def ao_visible(scene: PlaneScene, p: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """V (..., 1) at points of `scene.surface`: the closed forms above; 1 on a lone plane."""
    if scene.sphere is None:
        return np.ones(p.shape[:-1] + (1,))
    if scene.surface == "sphere":
        up = floor_frame(scene)[0]
        return (1 + np.broadcast_to(normal, p.shape) @ up)[..., None] / 2
    d = norm(sub(p, scene.sphere.center), keepdims=True)
    return 1 - (scene.sphere.radius / d) ** 3


def lit(scene: PlaneScene, p: np.ndarray, light: np.ndarray) -> np.ndarray:
    """1 where the light is not blocked by the sphere (..., 1); the cosine term decides the rest."""
    if scene.sphere is None or scene.surface == "sphere":
        return np.ones(p.shape[:-1] + (1,))
    return (~segment_crosses_sphere(scene, p, light))[..., None].astype(float)


__all__ = ["MIN_FLOOR_RATIO", "NotAnalytic", "ao_visible", "check_resting", "floor_frame", "hit_sphere", "lit",
           "segment_crosses_sphere"]
