"""Equal-probability histogram cells for a warp's chi-square tests, from the pdf's own marginal CDFs.

The cell edges in s are the quantiles k/res of the pdf's marginal distribution
in s (the density integrated over t), the edges in t likewise; an axis whose
marginal is uniform gets exactly uniform edges. Every cell of a separable pdf
then expects N / res^2 samples, however peaked the pdf: Beckmann at alpha 0.01,
whose mass lies in cos theta > 0.9995, gets its rows where the mass is. The
edges depend on the pdf only (and on the precision of the samples, see below),
never on the sample values, so the chi-square test stays valid.

Quantiles are found hierarchically: integrate the density over 256 strips (the
adaptive rule of harness.statistics.cubature), find the strip holding each quantile, then
halve it 24 times, all quantiles at once (to about 2e-10 in x; the strip masses
are known to 1e-8 of the mass, and a float32 pdf's own noise limits it sooner).
They are of the pdf's own mass, so a pdf off by a constant factor gets the same
cells (the normalisation check and the chi-square's N * cell integral still
catch it).

Float32 samples sit up to FLOAT32_QUANTUM / 2 from where exact arithmetic
would put them. Where the density is large, that moves measurable mass across a
cell edge (Beckmann at alpha 0.01: 0.2 % of the samples per quantum of cos theta
near the pole; Mitsuba's and our float32 samplers were measured off by up to half
a quantum), so an axis gets fewer equal-probability cells until the expected
noncentrality the rounding adds to the statistic is below ROUNDING_NONCENTRALITY.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from harness.statistics.cubature import integrate_regions, uniform_edges
from harness.statistics.constants import FLOAT32_QUANTUM, HISTOGRAM_RES, ROUNDING_NONCENTRALITY, WARP_SAMPLES

Density = Callable[[np.ndarray, np.ndarray], np.ndarray]

#: Pieces across a strip (its edges), so that a peak narrow in the other coordinate is not stepped over.
_UNIFORM_ACROSS = np.linspace(0.0, 1.0, 5)
#: At most this many pieces across a strip when they follow the other axis' quantiles.
_MAX_ACROSS = 8
#: Strips of the first level of the quantile search, shared by all quantiles.
_FIRST_STRIPS = 256
#: Halvings after the first level: 2^-8 * 2^-24 = 2^-32, about 2.3e-10, far below float32's quantum of 2^-24 (the
#: cells need not be exactly equal: any cells fixed before the samples give a valid test, their integrals exact).
_LEVELS = 24
#: Relative and absolute accuracy of the strip integrals behind the quantiles (densities of mass about 1). A
#: float32 pdf is noisy at about 1e-6 (its input rounded to float32): a tighter tolerance would refine forever.
#: 1e-8 of the mass moves a quantile by 0.01 of 10^6 samples; a pdf that jumps along a diagonal (a triangle on the
#: tent's square) refines strips across the jump down to that: 2.8 s for its cells, 5.5 s at 1e-14.
_RTOL, _ATOL = 1e-5, 1e-8
#: An axis whose res equal strips hold equal masses to this relative accuracy gets exactly uniform edges.
_UNIFORM_SNAP = 1e-6


@dataclass(frozen=True)
class Bins:
    """The cell edges of a histogram over the parameter square, in s (rows) and t (columns)."""

    s_edges: np.ndarray
    t_edges: np.ndarray
    #: "equal-probability" (from the pdf's marginals) or "uniform" (a fallback for a pdf with no usable mass).
    kind: str = "uniform"
    #: Cells per axis asked for; fewer on an axis where float32 rounding of the samples limits them.
    requested: int = HISTOGRAM_RES
    #: Why an axis has fewer cells than requested (None: it has them all).
    limited_by: str | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.s_edges) - 1, len(self.t_edges) - 1

    def describe(self) -> str:
        """A few words for reports, e.g. "51x51 equal-probability"."""
        rows, cols = self.shape
        text = f"{rows}x{cols} {self.kind}"
        return text + (f" ({self.limited_by})" if self.limited_by else "")

    def same_edges(self, other: "Bins") -> bool:
        """Whether both have the same cells (then one histogram serves both)."""
        return np.array_equal(self.s_edges, other.s_edges) and np.array_equal(self.t_edges, other.t_edges)

    def to_json(self) -> dict:
        out = {"cells": list(self.shape), "binning": self.kind}
        if self.limited_by:
            out["cells_limited_by"] = self.limited_by
        return out


def uniform_bins(res: int = HISTOGRAM_RES) -> Bins:
    """A res x res grid of equal cells."""
    edges = uniform_edges(res)
    return Bins(edges, edges, "uniform", res)


def _strip_masses(density: Density, axis: int, starts: np.ndarray, widths: np.ndarray,
                  across: np.ndarray = _UNIFORM_ACROSS) -> np.ndarray:
    """Integral of the density over [start, start + width] along `axis`, all of [0, 1] across it.

    `across`: edges splitting [0, 1] across the strip into pieces integrated apart (default 4 equal ones).
    """
    pieces = len(across) - 1
    starts, widths = np.repeat(starts, pieces), np.repeat(widths, pieces)
    lo = np.tile(across[:-1], len(starts) // pieces)
    step = np.tile(np.diff(across), len(starts) // pieces)
    if axis == 0:
        values, _ = integrate_regions(density, starts, lo, widths, step, atol=_ATOL, rtol=_RTOL)
    else:
        values, _ = integrate_regions(density, lo, starts, step, widths, atol=_ATOL, rtol=_RTOL)
    return values.reshape(-1, pieces).sum(axis=1)


def marginal_quantiles(density: Density, fractions: np.ndarray, axis: int = 0,
                       across: np.ndarray = _UNIFORM_ACROSS) -> np.ndarray | None:
    """Points x in [0, 1] where the marginal CDF along `axis` reaches each fraction of the total mass.

    density(s, t) on [0,1]^2 need not integrate to 1 (the fractions are of its own mass). On a flat
    stretch of the CDF the lowest such point is returned. Accurate to about 2e-10 in x (the search
    halves each quantile's strip down to 2^-32). None when the density has no finite, non-negative,
    positive mass (no quantiles exist). `across`: see _strip_masses.
    """
    fractions = np.asarray(fractions, dtype=np.float64)
    first = _strip_masses(density, axis, uniform_edges(_FIRST_STRIPS)[:-1], np.full(_FIRST_STRIPS, 1 / _FIRST_STRIPS),
                          across)
    total = float(first.sum())
    if not np.all(np.isfinite(first)) or np.any(first < 0) or not total > 0:
        return None
    target = fractions * total
    cum = np.cumsum(first)
    # The first strip whose right end reaches the target (the last one if rounding left it short).
    i = np.minimum(np.searchsorted(cum, target, side="left"), _FIRST_STRIPS - 1)
    before = cum[i] - first[i]
    start = i / _FIRST_STRIPS
    width = np.full(len(fractions), 1 / _FIRST_STRIPS)
    for _ in range(_LEVELS):
        width = width / 2
        left = np.maximum(np.nan_to_num(_strip_masses(density, axis, start, width, across)), 0.0)
        right = before + left < target
        before = np.where(right, before + left, before)
        start = np.where(right, start + width, start)
    mass = np.maximum(np.nan_to_num(_strip_masses(density, axis, start, width, across)), 0.0)
    inside = np.clip((target - before) / np.where(mass > 0, mass, 1.0), 0.0, 1.0)
    return np.clip(start + np.where(mass > 0, inside, 0.0) * width, 0.0, 1.0)


def _edges(quantiles: np.ndarray) -> np.ndarray:
    """0, the quantiles (strictly increasing, duplicates dropped), 1."""
    inner = np.unique(quantiles[(quantiles > 0) & (quantiles < 1)])
    return np.concatenate([[0.0], inner, [1.0]])


def rounding_noncentrality(density: Density, edges: np.ndarray, axis: int, samples: int, quantum: float,
                           across: np.ndarray = _UNIFORM_ACROSS) -> float:
    """Expected noncentrality added to a chi-square statistic by samples rounded across the inner edges.

    A sample lands up to quantum / 2 from its exact place, so the mass within quantum of an edge
    (m = f * quantum for a marginal density f there) is split at a point uniform in that window: the
    mass moved has variance m^2 / 12. Summed over edges, weighted by the cells they bound:
    samples * sum over cells of (var(lower edge) + var(upper edge)) / cell mass.
    """
    inner = edges[1:-1]
    if not len(inner) or quantum <= 0:
        return 0.0
    lo = np.clip(inner - quantum / 2, 0.0, 1.0)
    near = _strip_masses(density, axis, lo, np.clip(inner + quantum / 2, 0.0, 1.0) - lo, across)
    return _noncentrality(near, _strip_masses(density, axis, edges[:-1], np.diff(edges), across), samples)


def _noncentrality(near: np.ndarray, cells: np.ndarray, samples: int) -> float:
    """rounding_noncentrality from the masses within quantum / 2 of each inner edge and the masses of the cells."""
    total = cells.sum()
    if not total > 0:  # no mass to move (a pdf that is 0 everywhere): rounding changes nothing
        return 0.0
    var = np.concatenate([[0.0], (near / total) ** 2 / 12, [0.0]])
    cell = np.maximum(cells / total, 1e-300)
    return float(samples * np.sum((var[:-1] + var[1:]) / cell))


def _most_cells(edges_for: Callable[[int], np.ndarray | None], noncentrality: Callable[[np.ndarray], float],
                res: int) -> tuple[np.ndarray, bool] | None:
    """edges_for(res), or edges_for(n) for the largest n < res whose rounding noncentrality is at most
    ROUNDING_NONCENTRALITY (or one cell). Returns (edges, limited) or None if edges_for gives none."""
    edges = edges_for(res)
    if edges is None:
        return None
    if noncentrality(edges) <= ROUNDING_NONCENTRALITY:
        return edges, False
    lo, hi, best = 1, res, uniform_edges(1)  # the noncentrality grows with the number of cells: bisect on it
    while hi - lo > 1:
        mid = (lo + hi) // 2
        candidate = edges_for(mid)
        if candidate is None:  # strips this wide miss a mass narrower than them: more cells see it
            lo = mid
        elif noncentrality(candidate) <= ROUNDING_NONCENTRALITY:
            lo, best = mid, candidate
        else:
            hi = mid
    return best, True


def _axis_edges(density: Density, axis: int, res: int, samples: int, quantum: float,
                across: np.ndarray) -> tuple[np.ndarray, bool] | None:
    """Equal-probability edges along one axis: res cells, or the most that float32 rounding allows.

    Returns (edges, limited) or None if the density has no usable mass.
    """
    def edges_for(n: int) -> np.ndarray | None:
        uniform = uniform_edges(n)
        masses = _strip_masses(density, axis, uniform[:-1], np.diff(uniform), across)
        total = masses.sum()
        if not np.all(np.isfinite(masses)) or np.any(masses < 0) or not total > 0:
            return None
        if np.max(np.abs(masses * n / total - 1.0)) <= _UNIFORM_SNAP:
            return uniform
        q = marginal_quantiles(density, np.arange(1, n) / n, axis, across)
        return None if q is None else _edges(q)

    return _most_cells(edges_for, lambda e: rounding_noncentrality(density, e, axis, samples, quantum, across), res)


def _pieces(edges: np.ndarray) -> np.ndarray:
    """At most _MAX_ACROSS + 1 of the edges (ends kept), as pieces to integrate across a strip."""
    keep = np.unique(np.round(np.linspace(0, len(edges) - 1, min(len(edges), _MAX_ACROSS + 1))).astype(int))
    return edges[keep]


def equal_probability_bins(density: Density, res: int = HISTOGRAM_RES, samples: int = WARP_SAMPLES,
                           quantum: float = 0.0) -> Bins:
    """Cells from the quantiles of the density's marginals in s and in t.

    density(s, t): the pdf on the parameter square (any positive multiple of it); res: cells per axis
    (default HISTOGRAM_RES); samples: the sample count of the test (default WARP_SAMPLES); quantum: the
    rounding step of the samples' coordinates (FLOAT32_QUANTUM for float32 samples, default 0 for exact
    ones). The t marginal is integrated across pieces that follow the s quantiles, so that a pdf
    concentrated in a sliver of s is still seen. Falls back to uniform_bins(res) when the density has
    no finite, non-negative, positive mass.
    """
    s_axis = _axis_edges(density, 0, res, samples, quantum, _UNIFORM_ACROSS)
    if s_axis is None:
        return uniform_bins(res)
    across = _pieces(s_axis[0]) if len(s_axis[0]) > 2 else _pieces(_edges(marginal_quantiles(
        density, np.arange(1, _MAX_ACROSS) / _MAX_ACROSS, 0)))
    t_axis = _axis_edges(density, 1, res, samples, quantum, across)
    if t_axis is None:
        return uniform_bins(res)
    return Bins(s_axis[0], t_axis[0], "equal-probability", res, _limits([s_axis[1], t_axis[1]]))


#: Cells at least, between two breaks, of a segment the pilot reached: a sliver of the mass (light leaving a glass
#: just above its horizon) gets edges of its own, so that the cell integrals see it.
_SEGMENT_CELLS = 4


def _segment_quantiles(values: np.ndarray, n: int, breaks: tuple[float, ...]) -> np.ndarray:
    """About n cells' inner edges at the quantiles of `values`, taken apart between the breaks: each segment a
    share of the n cells by its count, and at least _SEGMENT_CELLS where it holds enough values for them; each
    segment's least and greatest value an edge too."""
    bounds = np.concatenate([[-np.inf], np.sort(breaks), [np.inf]])
    out = []
    for lo, hi in zip(bounds[:-1], bounds[1:]):
        part = values[(values >= lo) & (values < hi)]
        if not len(part):
            continue
        cells = min(max(round(n * len(part) / max(len(values), 1)), _SEGMENT_CELLS), len(part) // 16)
        # The segment's extremes too: a band the pilot reached, however thin, is a cell of its own.
        out.append([part.min(), part.max()])
        if cells >= 2:
            out.append(np.quantile(part, np.arange(1, cells) / cells))
    return np.concatenate(out) if out else np.array([])


#: How far below ROUNDING_NONCENTRALITY the pilot's estimate must be for the cubature to be spared.
_SCREEN_MARGIN = 10.0


def pilot_noncentrality(ordered: np.ndarray, edges: np.ndarray, samples: int, quantum: float) -> float:
    """rounding_noncentrality estimated from a pilot sample's values (sorted) instead of the density: a cell's mass
    its share of the pilot (one point at least), the marginal density at an edge the larger of its two cells'
    (share + one point) / width. An estimate, leaning high, for screening only."""
    inner = edges[1:-1]
    if not len(inner) or quantum <= 0 or not len(ordered):
        return 0.0
    n = len(ordered)
    counts = np.diff(np.searchsorted(ordered, edges, side="left")).astype(np.float64)
    counts[-1] += n - counts.sum()  # the points at the last edge itself
    density = (counts + 1.0) / (n * np.diff(edges))
    near = np.maximum(density[:-1], density[1:]) * quantum
    return _noncentrality(near, np.maximum(counts, 1.0) / n, samples)


def pilot_bins(density: Density, pilot_s: np.ndarray, pilot_t: np.ndarray, res: int = HISTOGRAM_RES,
               samples: int = WARP_SAMPLES, quantum: float = 0.0, s_breaks: tuple[float, ...] = ()) -> Bins:
    """Cells at the quantiles of a pilot sample's marginals (parameters pilot_s, pilot_t of points drawn apart from
    the tested ones), as fine as the samples' rounding `quantum` allows (as equal_probability_bins). The pilot
    stands in for the quantile search of the pdf's marginals, which costs a thousand of its evaluations a cell
    edge: cells fixed before the tested samples are drawn give a valid test whatever they are, and the expected
    counts remain the pdf's integrals over them. A wrong sampler only makes the cells unequal under the pdf.
    `s_breaks`: edges in s kept whatever the pilot (where the density may jump: the domain's s_breaks), which no
    sample's rounding crosses; the quantiles are taken apart on each side of them (_segment_quantiles)."""
    def axis(values: np.ndarray, ax: int, across: np.ndarray, breaks: tuple[float, ...]) -> tuple[np.ndarray, bool]:
        def edges_for(n: int) -> np.ndarray:
            return _edges(np.concatenate([_segment_quantiles(values, n, breaks), breaks]))

        ordered = np.sort(values)

        def noncentrality(e: np.ndarray) -> float:
            # A break is a boundary no rounding crosses (the sign of z): the cells it splits count as one there.
            e = np.setdiff1d(e, breaks)
            if pilot_noncentrality(ordered, e, samples, quantum) <= ROUNDING_NONCENTRALITY / _SCREEN_MARGIN:
                return 0.0  # far below the limit by the pilot's estimate: spare the cubature of every edge's strip
            return rounding_noncentrality(density, e, ax, samples, quantum, across)
        return _most_cells(edges_for, noncentrality, res)

    s_edges, s_limited = axis(np.asarray(pilot_s, np.float64), 0, _UNIFORM_ACROSS, tuple(s_breaks))
    t_edges, t_limited = axis(np.asarray(pilot_t, np.float64), 1,
                              _pieces(s_edges) if len(s_edges) > 2 else _UNIFORM_ACROSS, ())
    return Bins(s_edges, t_edges, "pilot quantiles", res, _limits([s_limited, t_limited]))


#: A marginal CDF on [0, 1] (from 0 to 1) and its inverse.
Cdf = tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray]]


def _limits(limited: list[bool]) -> str | None:
    names = [name for name, lim in zip(("s", "t"), limited) if lim]
    return f"{' and '.join(names)} limited by float32 rounding of the samples" if names else None


def cdf_cells(s_axis: Cdf, t_axis: Cdf, res: int = HISTOGRAM_RES, samples: int = WARP_SAMPLES,
              quantum: float = 0.0) -> tuple[Bins, np.ndarray]:
    """The cells equal_probability_bins makes, for a density of independent s and t known by their marginal CDFs
    (a closed form: edges at exact quantiles, as few where float32 rounding limits them), and the exact
    probability of each cell."""
    def axis(cdf: Callable, inverse: Callable) -> tuple[np.ndarray, bool]:
        def noncentrality(e: np.ndarray) -> float:
            inner = e[1:-1]
            if not len(inner) or quantum <= 0:
                return 0.0
            near = cdf(np.clip(inner + quantum / 2, 0.0, 1.0)) - cdf(np.clip(inner - quantum / 2, 0.0, 1.0))
            return _noncentrality(near, np.diff(cdf(e)), samples)
        return _most_cells(lambda n: _edges(inverse(np.arange(1, n) / n)), noncentrality, res)

    (s, s_limited), (t, t_limited) = axis(*s_axis), axis(*t_axis)
    bins = Bins(s, t, "equal-probability", res, _limits([s_limited, t_limited]))
    return bins, np.outer(np.diff(s_axis[0](s)), np.diff(t_axis[0](t)))


def sample_quantum(*point_sets: np.ndarray) -> float:
    """FLOAT32_QUANTUM if every coordinate of every set is a float32 value (a float32 sampler), else 0."""
    for points in point_sets:
        finite = points[np.all(np.isfinite(points), axis=1)]
        if len(finite) and not np.array_equal(finite.astype(np.float32).astype(np.float64), finite):
            return 0.0
    return FLOAT32_QUANTUM


def bin_indices(edges: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The cell of each x: i with edges[i] <= x < edges[i + 1], values at or beyond the ends clipped in."""
    return np.clip(np.searchsorted(edges, x, side="right") - 1, 0, len(edges) - 2)
