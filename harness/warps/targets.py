"""What a warp's name promises: the closed-form density of each warp of the matrix, by Mitsuba's name.

A warp called square_to_tent must sample (1 - |x|)(1 - |y|) on [-1, 1]^2 whatever its own pdf says; its samples
are tested against that density and its pdf compared with it (evaluate_warp's `target`). The conventions are
those of renderer/warp.h, include/mcval_warps.h and Mitsuba's mi.warp: densities with respect to area on the
square, the tent's square and the unit disk, with respect to solid angle on the sphere and the hemisphere
(z up); Beckmann's is the density of the microfacet normal m, D(m) cos(theta_m) with the roughness alpha.
Every density is float64 and 0 outside its domain (Domain.inside, with its float32 slack).
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Callable

import numpy as np

from harness.statistics.constants import HISTOGRAM_RES
from harness.warps.bins import Bins, Cdf, cdf_cells
from harness.warps.domains import get_domain

Density = Callable[[np.ndarray, "float | None"], np.ndarray]


def _square(p: np.ndarray, alpha: float | None) -> np.ndarray:
    return np.ones(len(p))


def _tent(p: np.ndarray, alpha: float | None) -> np.ndarray:
    return np.prod(np.clip(1.0 - np.abs(p), 0.0, None), axis=1)


def _constant(value: float) -> Density:
    return lambda p, alpha: np.full(len(p), value)


def _cosine(p: np.ndarray, alpha: float | None) -> np.ndarray:
    return np.clip(p[:, 2], 0.0, None) / np.pi


def _beckmann(p: np.ndarray, alpha: float | None) -> np.ndarray:
    """exp(-tan^2 / alpha^2) / (pi alpha^2 cos^3) for z > 0; tan^2 from x^2 + y^2, which does not cancel at the
    pole as 1 - z^2 does."""
    z = p[:, 2]
    up = z > 0
    zu = np.where(up, z, 1.0)
    tan2 = (p[:, 0] ** 2 + p[:, 1] ** 2) / (zu * zu)
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        e = np.exp(-tan2 / alpha**2)
        value = e / (np.pi * alpha**2 * zu**3)
    # Near the horizon exp underflows to 0 first (and cos^3 may too): the density is 0 there, not 0 / 0.
    return np.where(up & (e > 0), value, 0.0)


# Marginal CDFs on the domain's parameter square (harness.warps.domains: s is cos(theta) on the hemisphere,
# (z + 1) / 2 on the sphere, r^2 on the disk, (x + 1) / 2 on the tent's square; t is the azimuth / 2 pi or y),
# each with its inverse. Every target's s and t are independent.
_UNIFORM: Cdf = (lambda s: np.asarray(s, dtype=np.float64), lambda q: np.asarray(q, dtype=np.float64))
#: The tent's 1 - |x| on [-1, 1] with x = 2 s - 1: 2 s^2 up to 1/2, 1 - 2 (1 - s)^2 beyond.
_TENT: Cdf = (lambda s: np.where(s <= 0.5, 2 * s * s, 1 - 2 * (1 - s) ** 2),
              lambda q: np.where(q <= 0.5, np.sqrt(q / 2), 1 - np.sqrt((1 - q) / 2)))
#: cos(theta) / pi over solid angle is 2 s on [0, 1].
_COSINE: Cdf = (lambda s: np.asarray(s, dtype=np.float64) ** 2, np.sqrt)


def _beckmann_cdf(alpha: float) -> Cdf:
    """P(cos theta <= s) = P(tan^2 theta >= tan^2) = exp(-tan^2 / alpha^2), tan^2 = (1 - s^2) / s^2; inverse
    s = 1 / sqrt(1 - alpha^2 log q)."""
    def cdf(s: np.ndarray) -> np.ndarray:
        s = np.asarray(s, dtype=np.float64)
        safe = np.where(s > 0, s, 1.0)
        return np.where(s > 0, np.exp(-(1 - safe) * (1 + safe) / (safe * safe * alpha**2)), 0.0)

    def inverse(q: np.ndarray) -> np.ndarray:
        q = np.asarray(q, dtype=np.float64)
        with np.errstate(divide="ignore"):
            return np.where(q > 0, 1 / np.sqrt(1 - alpha**2 * np.log(np.where(q > 0, q, 1.0))), 0.0)
    return cdf, inverse


@dataclass(frozen=True)
class _Known:
    domain: str
    formula: str
    density: Density
    #: (s marginal, t marginal), given alpha.
    marginals: Callable[["float | None"], tuple[Cdf, Cdf]]
    takes_alpha: bool = False


#: Every warp mcval knows by name: its domain, its density as a formula, and the density itself.
KNOWN: dict[str, _Known] = {
    "square_to_uniform_square": _Known("square", "1 on [0,1]^2", _square, lambda a: (_UNIFORM, _UNIFORM)),
    "square_to_tent": _Known("tent", "(1-|x|)(1-|y|) on [-1,1]^2", _tent, lambda a: (_TENT, _TENT)),
    "square_to_uniform_disk": _Known("disk", "1/pi on the unit disk", _constant(1 / np.pi),
                                     lambda a: (_UNIFORM, _UNIFORM)),
    "square_to_uniform_sphere": _Known("sphere", "1/(4pi) on the sphere", _constant(1 / (4 * np.pi)),
                                       lambda a: (_UNIFORM, _UNIFORM)),
    "square_to_uniform_hemisphere": _Known("hemisphere", "1/(2pi) on the hemisphere", _constant(1 / (2 * np.pi)),
                                           lambda a: (_UNIFORM, _UNIFORM)),
    "square_to_cosine_hemisphere": _Known("hemisphere", "cos(theta)/pi on the hemisphere", _cosine,
                                          lambda a: (_COSINE, _UNIFORM)),
    "square_to_beckmann": _Known("hemisphere", "D(m) cos(theta_m), Beckmann", _beckmann,
                                 lambda a: (_beckmann_cdf(a), _UNIFORM), takes_alpha=True),
}


@dataclass(frozen=True)
class Target:
    """The density a warp of a known name must sample: `pdf` over points of its domain."""

    warp: str
    domain: str
    formula: str
    alpha: float | None = None

    @property
    def label(self) -> str:
        """e.g. "square_to_tent's (1-|x|)(1-|y|) on [-1,1]^2", "square_to_beckmann's D(m) cos(theta_m),
        Beckmann alpha=0.3"."""
        text = f"{self.warp}'s {self.formula}"
        return text if self.alpha is None else f"{text} alpha={self.alpha:g}"

    @property
    def key(self) -> str:
        """Short id, as the matrix's --only takes it: "tent", "beckmann:0.3"."""
        short = self.warp.removeprefix("square_to_")
        return short if self.alpha is None else f"{short}:{self.alpha:g}"

    def cells(self, samples: int, quantum: float = 0.0) -> tuple[Bins, np.ndarray]:
        """Its equal-probability cells over the parameter square for `samples` samples rounded by `quantum` (see
        warp_bins.cdf_cells: the quantiles of its marginals, exactly), and the probability of each cell."""
        s_axis, t_axis = KNOWN[self.warp].marginals(self.alpha)
        return cdf_cells(s_axis, t_axis, HISTOGRAM_RES, samples, quantum)

    def pdf(self, points: np.ndarray) -> np.ndarray:
        """The closed-form density at (N, dim) points, 0 outside the domain; float64."""
        points = np.asarray(points, dtype=np.float64)
        inside = get_domain(self.domain).inside(points)
        values = np.zeros(len(points))
        values[inside] = KNOWN[self.warp].density(points[inside], self.alpha)
        return values


def target_for(name: str, alpha: float | None = None) -> Target | None:
    """The target of the warp called `name`, or None if mcval knows no warp of that name.

    `name`: Mitsuba's name or its short form ("square_to_tent", "tent"), Beckmann's roughness either in it
    ("beckmann:0.3") or as `alpha`. Raises ValueError for Beckmann without its alpha, or with two different ones.
    """
    match = re.fullmatch(r"(?:square_to_)?([a-z_]+?)(?::([0-9.eE+-]+))?", name.strip())
    if match is None or f"square_to_{match.group(1)}" not in KNOWN:
        return None
    warp = f"square_to_{match.group(1)}"
    known = KNOWN[warp]
    in_name = float(match.group(2)) if match.group(2) else None
    if not known.takes_alpha:
        return None if in_name is not None else Target(warp, known.domain, known.formula)
    if in_name is not None and alpha is not None and not np.isclose(in_name, alpha):
        raise ValueError(f"{name} names alpha={in_name:g}, and alpha={alpha:g} was given")
    alpha = in_name if in_name is not None else alpha
    if alpha is None or not alpha > 0:
        raise ValueError(f"{warp} is judged against its closed form at its roughness: give it as "
                         f"'{warp.removeprefix('square_to_')}:0.3' or as its alpha (a positive number)")
    return Target(warp, known.domain, known.formula, float(alpha))


def known_names() -> list[str]:
    """Every name target_for knows, short forms, for messages."""
    return [w.removeprefix("square_to_") + (":ALPHA" if k.takes_alpha else "") for w, k in KNOWN.items()]
