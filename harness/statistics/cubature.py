"""Adaptive integration of a density over many rectangles (the cells of a grid) at once.

Each region is integrated with a 4x4 Gauss-Legendre rule, and again as two
halves split in s and as two halves split in t. Where either split changes the
estimate by more than the tolerance, the region is split along the axis that
changed it more, and the halves go on. Splitting one axis at a time resolves
features thin in one coordinate (Beckmann at alpha 0.01 puts its mass in
cos theta > 0.9995: a sliver of the lowest equal-probability row, a long thin
strip of a quantile search) without refining the other. A region is also split
when a corner value times its area dwarfs its integral: a spike narrower than
the nodes' spacing (the pole at alpha 0.001) is invisible to every Gauss
estimate but not to the corner it sits on. All regions of one level go to the
density in one vectorised call. This keeps expected counts accurate for peaked
densities, where a fixed rule would make a correct warp fail its chi-square
test. `integrate_cells` takes grids with any edges (warp_bins' equal-probability
cells); `integrate_regions` any list of rectangles.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(4)
_NODES = (_NODES + 1.0) / 2.0  # on [0, 1]
_WEIGHTS = np.outer(_WEIGHTS, _WEIGHTS).ravel() / 4.0
_CORNERS = np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]])
#: A region whose largest corner value times its area exceeds this many times its integral is split even when
#: its estimates agree (see the module docstring).
SPIKE_RATIO = 8.0

#: Refinement stops here whatever the error (a discontinuous density would refine forever); each level halves
#: one axis of a region.
MAX_LEVEL = 40
#: Regions refined at once at the most; beyond, the remaining ones are accepted as they are. A density that jumps
#: along a line across the cells (a triangle's pdf on the tent's square) never converges: every level doubles the
#: regions on the line, and a larger budget only buys time (89 s for such a tent's cells at 400,000, 4 s here, the
#: integral no better). The matrix's warps refine at most 800 regions at once, Mitsuba's float32 Beckmann at
#: alpha 0.01 59,000 (chasing its own rounding): capped here, its cells and every other warp's are unchanged.
MAX_REGIONS = 20_000


@dataclass
class CellIntegrals:
    """Integrals per cell, shape (res_s, res_t), and an estimate of their total absolute error."""

    values: np.ndarray
    error: float


def _rule(f: Callable, x0: np.ndarray, y0: np.ndarray, h: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre estimate over the regions [x0, x0+h] x [y0, y0+k], and the largest corner value of each."""
    xs = (x0[:, None] + h[:, None] * _NODES[None, :])[:, :, None]
    ys = (y0[:, None] + k[:, None] * _NODES[None, :])[:, None, :]
    xs, ys = np.broadcast_arrays(xs, ys)
    cx = x0[:, None] + h[:, None] * _CORNERS[None, :, 0]
    cy = y0[:, None] + k[:, None] * _CORNERS[None, :, 1]
    n = len(x0)
    values = np.asarray(f(np.concatenate([xs.reshape(n, -1), cx], axis=1).ravel(),
                          np.concatenate([ys.reshape(n, -1), cy], axis=1).ravel()), dtype=np.float64).reshape(n, -1)
    corners = np.nan_to_num(values[:, -4:], nan=0.0, neginf=0.0)
    return values[:, :-4] @ _WEIGHTS * h * k, corners.max(axis=1)


def integrate_regions(f: Callable[[np.ndarray, np.ndarray], np.ndarray], x0: np.ndarray, y0: np.ndarray,
                      h: np.ndarray, k: np.ndarray, atol: float = 1e-10,
                      rtol: float = 1e-6) -> tuple[np.ndarray, float]:
    """Integrate f(s, t) over each rectangle [x0, x0+h] x [y0, y0+k] (1D arrays of one length).

    A region is accepted once both of its splits change its estimate by less than
    max(atol, rtol * |estimate|) and no corner spike is left; the sum of those
    changes is returned as the error estimate (pessimistic: the estimate of the
    split that changed more is kept). Returns (integrals, error).
    """
    with np.errstate(invalid="ignore", over="ignore"):  # an infinite density gives inf and NaN estimates, not warnings
        return _integrate_regions(f, x0, y0, h, k, atol, rtol)


def _integrate_regions(f: Callable, x0: np.ndarray, y0: np.ndarray, h: np.ndarray, k: np.ndarray, atol: float,
                       rtol: float) -> tuple[np.ndarray, float]:
    x0, y0, h, k = (np.asarray(a, dtype=np.float64).ravel() for a in (x0, y0, h, k))
    owner = np.arange(len(x0))
    coarse, _ = _rule(f, x0, y0, h, k)
    total = np.zeros(len(x0))
    error = 0.0
    for level in range(MAX_LEVEL + 1):
        m = len(x0)
        # Halves of every region: split in s (left, right), then split in t (bottom, top).
        hx, ky = np.concatenate([h / 2, h / 2, h, h]), np.concatenate([k, k, k / 2, k / 2])
        hx0 = np.concatenate([x0, x0 + h / 2, x0, x0])
        hy0 = np.concatenate([y0, y0, y0, y0 + k / 2])
        halves, corner = _rule(f, hx0, hy0, hx, ky)
        halves, corner = halves.reshape(4, m), corner.reshape(4, m)
        split_s, split_t = halves[0] + halves[1], halves[2] + halves[3]
        ds, dt = np.abs(split_s - coarse), np.abs(split_t - coarse)
        along_s = ds >= dt
        fine = np.where(along_s, split_s, split_t)
        diff = np.maximum(ds, dt)
        tol = np.maximum(atol, rtol * np.abs(fine))
        excess = corner * (hx * ky).reshape(4, m) - SPIKE_RATIO * np.abs(halves)
        spike = excess.max(axis=0) > tol
        # A spike with agreeing estimates: split along the axis whose halves' corners differ more.
        quiet = spike & (diff <= tol)
        along_s[quiet] = (np.abs(corner[0] - corner[1]) >= np.abs(corner[2] - corner[3]))[quiet]
        done = (diff <= tol) & ~spike
        if level == MAX_LEVEL or 2 * np.count_nonzero(~done) > MAX_REGIONS:
            done[:] = True
        np.add.at(total, owner[done], fine[done])
        error += float(diff[done].sum())
        go = ~done
        if not go.any():
            break
        s_go, t_go = go & along_s, go & ~along_s
        x0 = np.concatenate([x0[s_go], x0[s_go] + h[s_go] / 2, x0[t_go], x0[t_go]])
        y0 = np.concatenate([y0[s_go], y0[s_go], y0[t_go], y0[t_go] + k[t_go] / 2])
        new_h = np.concatenate([h[s_go] / 2, h[s_go] / 2, h[t_go], h[t_go]])
        k = np.concatenate([k[s_go], k[s_go], k[t_go] / 2, k[t_go] / 2])
        h = new_h
        coarse = np.concatenate([halves[0][s_go], halves[1][s_go], halves[2][t_go], halves[3][t_go]])
        owner = np.concatenate([owner[s_go], owner[s_go], owner[t_go], owner[t_go]])
    return total, error


def uniform_edges(res: int) -> np.ndarray:
    """res + 1 equally spaced edges on [0, 1] (the last one exactly 1)."""
    return np.arange(res + 1) / res


def integrate_cells(f: Callable[[np.ndarray, np.ndarray], np.ndarray], res: int | np.ndarray,
                    t_edges: np.ndarray | None = None, atol: float = 1e-10, rtol: float = 1e-6) -> CellIntegrals:
    """Integrate f(s, t) over each cell of a grid on [0,1]^2.

    `res`: an int for a res x res grid of equal cells, or the increasing cell edges in s
    (any spacing); `t_edges`: the edges in t (default: the same as in s). Values have shape
    (len(s_edges) - 1, len(t_edges) - 1). Tolerances as in `integrate_regions`.
    """
    s_edges = uniform_edges(res) if np.isscalar(res) else np.asarray(res, dtype=np.float64)
    t_edges = s_edges if t_edges is None else np.asarray(t_edges, dtype=np.float64)
    ns, nt = len(s_edges) - 1, len(t_edges) - 1
    x0 = np.repeat(s_edges[:-1], nt)
    y0 = np.tile(t_edges[:-1], ns)
    h = np.repeat(np.diff(s_edges), nt)
    k = np.tile(np.diff(t_edges), ns)
    values, error = integrate_regions(f, x0, y0, h, k, atol, rtol)
    return CellIntegrals(values.reshape(ns, nt), error)
