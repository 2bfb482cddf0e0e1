"""The oracle of the area lights' closed forms, written apart from harness/closed_forms/area_lights.py: the
projected solid angle a light subtends at a point, integral of cos(theta_p) cos(theta_light) / r^2 over the
light's surface, by composite Gauss-Legendre quadrature (periodic trapezoid rule in azimuth)."""
from __future__ import annotations

import numpy as np


def _gauss(panels: int, nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of composite Gauss-Legendre quadrature on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    edges = np.linspace(0.0, 1.0, panels + 1)
    half = np.diff(edges) / 2
    mid = (edges[:-1] + edges[1:]) / 2
    return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()


def _kernel(p: np.ndarray, n: np.ndarray, x: np.ndarray, nx: np.ndarray) -> np.ndarray:
    """cos(theta_p) cos(theta_x) / r^2 from p (normal n) to surface points x (..., 3) with normals nx (the light
    emits along nx; nothing below p's horizon or behind the light counts)."""
    d = x - p
    r2 = np.sum(d * d, axis=-1)
    r = np.sqrt(r2)
    cos_p = np.clip(d @ n / r, 0, None)
    cos_x = np.clip(-np.sum(d * nx, axis=-1) / r, 0, None)
    return cos_p * cos_x / r2


def rectangle(corner: np.ndarray, e1: np.ndarray, e2: np.ndarray, p: np.ndarray, n: np.ndarray,
              panels: int = 8, nodes: int = 24) -> float:
    """Over the parallelogram corner + u e1 + v e2 (u, v in [0, 1]), emitting along e1 x e2 (unnormalised)."""
    t, w = _gauss(panels, nodes)
    u, v = np.meshgrid(t, t, indexing="ij")
    x = corner + u[..., None] * e1 + v[..., None] * e2
    normal = np.cross(e1, e2)
    area = np.linalg.norm(normal)
    return float(np.einsum("i,j,ij->", w, w, _kernel(p, n, x, normal / area)) * area)


def disk(center: np.ndarray, normal: np.ndarray, radius: float, p: np.ndarray, n: np.ndarray,
         panels: int = 8, nodes: int = 24, azimuths: int = 512) -> float:
    """Over the disk, emitting along `normal`: Gauss-Legendre in the radius, the trapezoid rule in azimuth."""
    a = np.cross(normal, [1.0, 0, 0] if abs(normal[0]) < 0.9 else [0, 1.0, 0])
    a /= np.linalg.norm(a)
    b = np.cross(normal, a)
    t, w = _gauss(panels, nodes)
    rho = radius * t
    phi = 2 * np.pi * np.arange(azimuths) / azimuths
    x = center + rho[:, None, None] * (np.cos(phi)[None, :, None] * a + np.sin(phi)[None, :, None] * b)
    f = _kernel(p, n, x, normal)
    return float(np.sum(w[:, None] * radius * rho[:, None] * f) * 2 * np.pi / azimuths)


def sphere(center: np.ndarray, radius: float, p: np.ndarray, n: np.ndarray,
           panels: int = 8, nodes: int = 24, azimuths: int = 512) -> float:
    """Over the cap of the sphere that p sees (about the axis towards p, out to the tangent cone), the rest
    facing away from p."""
    axis = p - center
    dist = np.linalg.norm(axis)
    axis /= dist
    a = np.cross(axis, [1.0, 0, 0] if abs(axis[0]) < 0.9 else [0, 1.0, 0])
    a /= np.linalg.norm(a)
    b = np.cross(axis, a)
    top = np.arccos(radius / dist)
    t, w = _gauss(panels, nodes)
    psi = top * t
    phi = 2 * np.pi * np.arange(azimuths) / azimuths
    nx = (np.cos(psi)[:, None, None] * axis
          + np.sin(psi)[:, None, None] * (np.cos(phi)[None, :, None] * a + np.sin(phi)[None, :, None] * b))
    f = _kernel(p, n, center + radius * nx, nx)
    return float(np.sum(w[:, None] * top * radius**2 * np.sin(psi)[:, None] * f) * 2 * np.pi / azimuths)
