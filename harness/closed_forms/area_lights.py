"""Area lights of constant radiance over a diffuse surface: the exact projected solid angle each subtends at a
point, so that the irradiance there is E = L * omega_perp and a diffuse surface of reflectance rho sends
rho / pi * E back (direct light only: a surface under a light reflects nothing onto itself).

omega_perp(p, n) = integral over the light of cos(theta_p) cos(theta_light) / r^2 dA, exact where the light is
wholly above the horizon of p (the callers check it where they read the scene):
  - a polygon (a rectangle): Lambert's formula, 1/2 sum_i beta_i n . gamma_i, beta_i the angle the edge
    (v_i, v_i+1) subtends at p and gamma_i the unit normal of the triangle (p, v_i+1, v_i); the vertices go
    counter-clockwise about the light's emitting normal. 0 behind the light's plane (it emits on one side);
  - a disk parallel to the surface and facing it, radius a, centre at height h and horizontal distance s:
    pi / 2 * (1 - (s^2 + h^2 - a^2) / sqrt((s^2 + h^2 + a^2)^2 - 4 a^2 s^2)), pi sin^2(alpha) on its axis;
  - a sphere of radius R, centre at distance d: pi (R / d)^2 cos(theta), theta the centre's angle from n.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.closed_forms.vectors import dot, norm, sub


@dataclass(frozen=True)
class PolygonLight:
    """A planar convex polygon (a rectangle) that emits `radiance` from its front side."""

    vertices: np.ndarray  # (k, 3), counter-clockwise about `normal`
    normal: np.ndarray    # unit, the side it emits to
    radiance: np.ndarray  # (3,)


@dataclass(frozen=True)
class DiskLight:
    """A disk that emits `radiance` from its front side."""

    center: np.ndarray
    normal: np.ndarray    # unit, the side it emits to
    radius: float
    radiance: np.ndarray


@dataclass(frozen=True)
class SphereLight:
    """A sphere that emits `radiance` outwards from every point."""

    center: np.ndarray
    radius: float
    radiance: np.ndarray


AreaLight = PolygonLight | DiskLight | SphereLight


def _cross(a: list, b: list) -> list:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def polygon_omega(light: PolygonLight, p: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Lambert's formula (...,) at points p (..., 3) with unit normals n ((3,) or (..., 3)); 0 behind the light."""
    total = np.zeros(np.shape(p)[:-1])
    k = len(light.vertices)
    for i in range(k):
        a, b = sub(light.vertices[i], p), sub(light.vertices[(i + 1) % k], p)
        c = _cross(b, a)  # the triangle (p, v_i+1, v_i): outwards of the solid angle seen from the front
        length = norm(c)
        beta = np.arctan2(length, dot(a, b))
        with np.errstate(invalid="ignore", divide="ignore"):
            total += np.where(length > 0, beta * dot(n, c) / length, 0.0)
    front = dot(sub(p, light.vertices[0]), light.normal) > 0
    return np.where(front, total / 2, 0.0)


def disk_omega(light: DiskLight, p: np.ndarray, n: np.ndarray) -> np.ndarray:
    """The exact projected solid angle (...,) of a disk parallel to the surface (light.normal = -n) above it."""
    to_center = sub(light.center, p)
    h = dot(to_center, n)
    s2 = np.maximum(dot(to_center, to_center) - h * h, 0.0)
    a2 = light.radius**2
    q = s2 + h * h
    return np.pi / 2 * (1 - (q - a2) / np.sqrt((q + a2) ** 2 - 4 * a2 * s2))


def disk_omega_on_axis(light: DiskLight, h: np.ndarray) -> np.ndarray:
    """pi sin^2(alpha) at height h on the disk's axis: the check of disk_omega where s = 0."""
    return np.pi * light.radius**2 / (light.radius**2 + np.asarray(h) ** 2)


def sphere_omega(light: SphereLight, p: np.ndarray, n: np.ndarray) -> np.ndarray:
    """pi (R/d)^2 cos(theta) (...,) for a sphere wholly above the horizon of each point."""
    to_center = sub(light.center, p)
    d2 = dot(to_center, to_center)
    return np.pi * light.radius**2 * dot(to_center, n) / (d2 * np.sqrt(d2))


def omega(light: AreaLight, p: np.ndarray, n: np.ndarray) -> np.ndarray:
    """The projected solid angle (...,) the light subtends at points p (..., 3) with unit normals n."""
    if isinstance(light, PolygonLight):
        return polygon_omega(light, p, n)
    if isinstance(light, DiskLight):
        return disk_omega(light, p, n)
    return sphere_omega(light, p, n)


def irradiance(lights, p: np.ndarray, n: np.ndarray) -> np.ndarray:
    """E (..., 3): the sum of L * omega_perp over the lights, a channel at a time."""
    out = np.zeros(np.shape(p)[:-1] + (3,))
    for light in lights:
        w = omega(light, p, n)
        for c in range(3):
            out[..., c] += light.radiance[c] * w
    return out


def lowest_height(light: AreaLight, origin: np.ndarray, up: np.ndarray) -> float:
    """The height above the plane (origin, up) of the light's lowest point: where it is positive the whole light
    is above the horizon of every point of that plane, where the closed forms are exact."""
    if isinstance(light, PolygonLight):
        return float(np.min((light.vertices - origin) @ up))
    if isinstance(light, SphereLight):
        return float((light.center - origin) @ up - light.radius)
    rim = light.radius * np.sqrt(max(0.0, 1 - float(light.normal @ up) ** 2))
    return float((light.center - origin) @ up - rim)


__all__ = ["AreaLight", "DiskLight", "PolygonLight", "SphereLight", "disk_omega",
           "disk_omega_on_axis", "irradiance", "lowest_height", "omega", "polygon_omega", "sphere_omega"]
