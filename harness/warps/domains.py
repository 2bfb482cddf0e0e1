"""The domains a warp can map to, each with a map onto the parameter square [0,1]^2.

Every map is measure-preserving up to a constant (`measure`), so a density p on
the domain is the density p * measure on the parameter square. Directions use
(s, t) = (cos theta mapped to [0,1], phi / 2 pi); the disk uses (r^2, phi / 2 pi).
Each domain also tells which points lie on its boundary: the sides of the square
and the tent, the rim of the disk, the horizon z = 0 of the hemisphere; the
sphere has none.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from harness.statistics.constants import UNIT_TOLERANCE

TWO_PI = 2.0 * np.pi


@dataclass(frozen=True)
class Domain:
    """A warp's target domain and its parameterisation."""

    name: str
    dim: int
    #: Size of the domain (area or solid angle): the constant Jacobian of the parameter map.
    measure: float
    to_param: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
    from_param: Callable[[np.ndarray, np.ndarray], np.ndarray]
    contains: Callable[[np.ndarray], np.ndarray]
    #: Points of the ambient space outside the domain, where the pdf must be 0 (None: there are none).
    outside: Callable[[np.random.Generator, int], np.ndarray] | None
    #: on_boundary(points, tol): which points lie within distance tol of the domain's edge (see BOUNDARY_TOLERANCE).
    on_boundary: Callable[[np.ndarray, float], np.ndarray]
    #: Values of s where densities on the domain commonly jump (the sphere's horizon, where a BSDF's reflection
    #: ends): cells from a pilot sample keep an edge there, so that no cell integral straddles the jump.
    s_breaks: tuple[float, ...] = ()

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Which points are finite and in the domain (NaN and Inf count as outside)."""
        finite = np.isfinite(points)
        return np.all(finite, axis=1) & self.contains(np.where(finite, points, 0.0))


def _azimuth(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    return np.mod(np.arctan2(y, x) / TWO_PI, 1.0)


def _direction(z: np.ndarray, t: np.ndarray) -> np.ndarray:
    r = np.sqrt(np.clip(1.0 - z * z, 0.0, None))
    phi = TWO_PI * t
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def _unit(p: np.ndarray) -> np.ndarray:
    return np.abs(np.linalg.norm(p, axis=-1) - 1.0) <= UNIT_TOLERANCE


def _box_edge(lo: float, hi: float) -> Callable[[np.ndarray, float], np.ndarray]:
    """Points with a coordinate within tol of lo or hi (a side or a corner of the box [lo, hi]^2)."""
    def on_boundary(p: np.ndarray, tol: float) -> np.ndarray:
        return np.any((np.abs(p - lo) <= tol) | (np.abs(p - hi) <= tol), axis=1)
    return on_boundary


def _no_boundary(p: np.ndarray, tol: float) -> np.ndarray:
    return np.zeros(len(p), dtype=bool)


def _box_outside(lo: float, hi: float) -> Callable[[np.random.Generator, int], np.ndarray]:
    """Points in a margin around the box [lo, hi]^2, none of them inside it."""
    def sample(rng: np.random.Generator, n: int) -> np.ndarray:
        width = hi - lo
        p = rng.uniform(lo - width, hi + width, size=(4 * n, 2))
        p = p[~np.all((p >= lo) & (p <= hi), axis=1)]
        return p[:n]
    return sample


def _disk_outside(rng: np.random.Generator, n: int) -> np.ndarray:
    r = rng.uniform(1.0 + 1e-3, 2.0, n)
    phi = rng.uniform(0.0, TWO_PI, n)
    return np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1)


def _below_horizon(rng: np.random.Generator, n: int) -> np.ndarray:
    z = -rng.uniform(1e-3, 1.0, n)
    return _direction(z, rng.uniform(0.0, 1.0, n))


SQUARE = Domain(
    "square", 2, 1.0,
    to_param=lambda p: (p[:, 0], p[:, 1]),
    from_param=lambda s, t: np.stack([s, t], axis=-1),
    contains=lambda p: np.all((p >= 0.0) & (p <= 1.0), axis=1),
    outside=_box_outside(0.0, 1.0),
    on_boundary=_box_edge(0.0, 1.0),
)

TENT = Domain(
    "tent", 2, 4.0,
    to_param=lambda p: ((p[:, 0] + 1.0) / 2.0, (p[:, 1] + 1.0) / 2.0),
    from_param=lambda s, t: np.stack([2.0 * s - 1.0, 2.0 * t - 1.0], axis=-1),
    contains=lambda p: np.all(np.abs(p) <= 1.0, axis=1),
    outside=_box_outside(-1.0, 1.0),
    on_boundary=_box_edge(-1.0, 1.0),
)

DISK = Domain(
    "disk", 2, np.pi,
    to_param=lambda p: (np.sum(p * p, axis=1), _azimuth(p[:, 0], p[:, 1])),
    from_param=lambda s, t: np.sqrt(s)[:, None] * np.stack([np.cos(TWO_PI * t), np.sin(TWO_PI * t)], axis=-1),
    contains=lambda p: np.sum(p * p, axis=1) <= 1.0 + UNIT_TOLERANCE,
    outside=_disk_outside,
    on_boundary=lambda p, tol: np.abs(np.linalg.norm(p, axis=1) - 1.0) <= tol,
)

SPHERE = Domain(
    "sphere", 3, 4.0 * np.pi,
    to_param=lambda p: ((p[:, 2] + 1.0) / 2.0, _azimuth(p[:, 0], p[:, 1])),
    from_param=lambda s, t: _direction(2.0 * s - 1.0, t),
    contains=_unit,
    outside=None,
    on_boundary=_no_boundary,
    s_breaks=(0.5,),
)

HEMISPHERE = Domain(
    "hemisphere", 3, TWO_PI,
    to_param=lambda p: (p[:, 2], _azimuth(p[:, 0], p[:, 1])),
    from_param=_direction,
    contains=lambda p: _unit(p) & (p[:, 2] >= 0.0),
    outside=_below_horizon,
    on_boundary=lambda p, tol: np.abs(p[:, 2]) <= tol,
)

DOMAINS = {d.name: d for d in (SQUARE, TENT, DISK, SPHERE, HEMISPHERE)}


def get_domain(name: str) -> Domain:
    """The domain called `name`; a ValueError lists the known ones otherwise."""
    try:
        return DOMAINS[name]
    except KeyError:
        raise ValueError(f"unknown domain {name!r}: expected one of {', '.join(DOMAINS)}") from None
