"""The bias a comparison finds half of the time: per element of (..., C) statistics, the relative bias at which
the Welch test rejects in at least one channel with probability IMAGE_POWER_TARGET (the noncentral t), found
by a root search that evaluates each element only until its estimate settles."""
from __future__ import annotations

from typing import Callable

import numpy as np

from harness.statistics.constants import IMAGE_POWER_TARGET
from harness.statistics.distributions import nct_cdf, nct_sf, norm_cdf, norm_pdf, norm_ppf
from harness.statistics.family_level import channel_union
from harness.statistics.welch import BatchStats, critical_t

#: The root search of `increasing_root` (regula falsi, Anderson-Bjorck) stops when no element's estimate moves
#: by more than this, relative to its first bracket, or after this many steps.
_ROOT_TOLERANCE = 1e-10
_ROOT_STEPS = 100
#: The first bracket is probed at the normal approximation's root (within ~1.5 % at 7 dof and up), then by a
#: Newton step past the root, then this far (relative) and 4x further each time the power has not crossed its
#: target: at most _PROBES probes.
_PROBE = 0.02
_PROBES = 4
#: Newton steps on the normal approximation.
_MODEL_STEPS = 5

Excess = Callable[[np.ndarray, np.ndarray], np.ndarray]


def half_power_bias(reference: BatchStats, se: np.ndarray, dof: np.ndarray, level: float,
                    rho: float, power: float | tuple[float, ...] = IMAGE_POWER_TARGET) -> np.ndarray:
    """Per element of (..., C) statistics: the relative bias b (the test scaled by 1 + b) that makes the
    test at `level` reject in at least one of the C channels with probability `power` (IMAGE_POWER_TARGET,
    a half, unless given; several powers, searched together, give the result a last axis, one per power).

    Channel c's t is noncentral with noncentrality b |mean_c| / se_c and the Welch degrees of freedom.
    Channels correlated by `rho` count as `channel_union` of them at the null does: P(any) is
    1 - prod_c (1 - power_c)^(union / C), exact for independent (rho = 0) and for identical (rho = 1)
    channels. Infinite where no channel has a non-zero mean."""
    live, root = _search(reference, se, dof, level, rho, np.atleast_1d(power))
    if np.ndim(power):
        live = live[..., None]
    else:
        root = root[..., 0]
    return np.where(live, root, np.inf)


def _search(reference: BatchStats, se: np.ndarray, dof: np.ndarray, level: float, rho: float,
            powers: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The elements with a non-zero mean in some channel, and the roots (per element and power)."""
    scale = np.where(np.isfinite(reference.mean) & (se > 0), np.abs(reference.mean) / np.where(se > 0, se, 1.0), 0.0)
    scale = np.atleast_2d(scale)
    dof = np.broadcast_to(np.atleast_2d(dof), scale.shape)
    crit = critical_t(level, dof)
    best = scale.max(axis=-1, keepdims=True)
    share = channel_union(level, scale.shape[-1], rho) / scale.shape[-1]
    live = best[..., 0] > 0
    hi = np.where(best > 0, (2.0 * crit.max(axis=-1, keepdims=True) + 8.0) / np.where(best > 0, best, 1.0), 1.0)
    hi = hi.reshape(-1)
    # An element without a mean is searched nowhere: it ends at its bracket's end, as one whose power does
    # not cross the target there.
    root = np.repeat(hi[:, None], powers.size, axis=1)
    index = np.flatnonzero(live.reshape(-1))
    if not index.size:
        return live, root.reshape(*live.shape, powers.size)
    # Searched as (elements, channels) rows, each row's channels together, and equal rows (the tiles of a flat
    # region) once.
    rows = tuple(np.reshape(r, (-1, scale.shape[-1]))[index] for r in (scale, crit, dof))
    first, copies = np.arange(index.size), np.arange(index.size)
    if index.size > 1:
        _, first, copies = np.unique(np.concatenate(rows, axis=-1), axis=0, return_index=True, return_inverse=True)
        rows, copies = tuple(r[first] for r in rows), copies.reshape(-1)
    # Each row once per power.
    rows = tuple(np.repeat(r, powers.size, axis=0) for r in rows)
    power = np.tile(powers, first.size)
    target = norm_ppf(1.0 - power)

    def excess(b: np.ndarray, at: np.ndarray) -> np.ndarray:
        """P(some channel rejects at bias b) - power for the rows `at`, on the probit scale (where the power
        curve is nearly straight, so the secant steps land close): increasing in b."""
        row_scale, row_crit, row_dof = (r[at] for r in rows)
        nc = b[:, None] * row_scale
        with np.errstate(all="ignore"):  # scipy's nct returns NaN for some far tails: 0 below, a step above
            upper, lower = nct_sf(row_crit, row_dof, nc), nct_cdf(-row_crit, row_dof, nc)
        channel = np.where(np.isnan(upper), (nc > row_crit).astype(float), upper) + np.nan_to_num(lower, nan=0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            missed = np.exp(share * np.sum(np.log1p(-np.minimum(channel, 1.0)), axis=-1))
            return np.clip(target[at] - norm_ppf(missed), -40.0, 40.0)

    # At b = 0 each channel rejects at the level itself.
    with np.errstate(divide="ignore"):
        at_zero = np.clip(target - norm_ppf((1.0 - level) ** (share * scale.shape[-1])), -40.0, 40.0)
    top = np.repeat(hi[index][first], powers.size)
    guess, slope = _model_root(*rows, share, power, top)
    probes = _Probes(excess, guess, slope, top, at_zero)
    probes.run(np.arange(top.size), _PROBES)
    found = increasing_root(excess, *probes.brackets())
    root[index] = found.reshape(-1, powers.size)[copies]
    return live, root.reshape(*live.shape, powers.size)


def _model_root(scale: np.ndarray, crit: np.ndarray, dof: np.ndarray, share: float, power: np.ndarray,
                hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The root under the normal approximation to the noncentral t (Abramowitz & Stegun 26.7.10), by Newton's
    method from the best channel's own root, right of it (log P(no channel rejects) is concave and decreasing
    in b, so the steps approach it from the right), and the slope of the probit excess there."""
    shift = crit * (1.0 - 1.0 / (4.0 * dof))
    width = np.sqrt(1.0 + crit * crit / (2.0 * dof))
    best = np.argmax(scale, axis=-1)[:, None]
    b = (np.take_along_axis(shift + width * norm_ppf(1.0 - (1.0 - power) ** (1.0 / share))[:, None], best, -1)
         / np.take_along_axis(scale, best, -1))[:, 0]
    aim = np.log1p(-power)
    with np.errstate(all="ignore"):
        for _ in range(_MODEL_STEPS):
            up, down = (b[:, None] * scale - shift) / width, (-b[:, None] * scale - shift) / width
            kept = np.maximum(norm_cdf(-up) - norm_cdf(down), 1e-300)
            gap = share * np.sum(np.log(kept), axis=-1) - aim
            slope = -share * np.sum(scale / width * (norm_pdf(up) - norm_pdf(down)) / kept, axis=-1)
            step = np.where(np.isfinite(gap / slope), gap / slope, 0.0)
            b = np.clip(b - step, 0.0, b)
            if not np.any(np.abs(step) > 1e-4 * b):  # far closer than the approximation itself
                break
        # d/db of norm_ppf(1 - power) - norm_ppf(P(no channel rejects)), at P = 1 - power.
        probit_slope = -(1.0 - power) * slope / norm_pdf(norm_ppf(1.0 - power))
    return np.where(np.isfinite(b) & (b > 0), np.minimum(b, hi), 0.5 * hi), probit_slope


class _Probes:
    """Per element, the bracket [lo, top] of the root of the increasing `f` (f(0) = `at_zero`) that probing has
    found (f_top NaN while top is only the search's end, hi), f at its ends, and where to probe next: first
    at `start`, then by a Newton step with `slope` a quarter past the root, then _PROBE, 4 _PROBE, ... on
    from the last probe on the side the root lies, never beyond [0, hi]."""

    def __init__(self, f: Excess, start: np.ndarray, slope: np.ndarray, hi: np.ndarray, at_zero: np.ndarray):
        n = start.size
        self.f, self.slope, self.hi = f, slope, hi
        self.lo, self.top = np.zeros(n), hi.copy()
        self.f_lo, self.f_top = at_zero.astype(np.float64), np.full(n, np.nan)
        self.x, self.step, self.count = start.copy(), np.full(n, _PROBE), np.zeros(n, dtype=np.int64)
        self.open = at_zero < 0.0  # to be probed until both ends of its bracket are probes

    def run(self, rows: np.ndarray, rounds: int) -> None:
        """Up to `rounds` probes of each of `rows` still open."""
        for _ in range(rounds):
            rows = rows[self.open[rows]]
            if not rows.size:
                return
            x = self.x[rows]
            fx = self.f(x, rows)
            up = fx >= 0.0
            self.top[rows[up]], self.f_top[rows[up]] = x[up], fx[up]
            self.lo[rows[~up]], self.f_lo[rows[~up]] = x[~up], fx[~up]
            # Done when both ends are probes, or when probed below the root at hi itself (no crossing).
            done = (~np.isnan(self.f_top[rows]) & (self.lo[rows] > 0.0)) | (~up & (x >= self.hi[rows]))
            self.open[rows[done]] = False
            rows, fx, x = rows[~done], fx[~done], x[~done]
            first = self.count[rows] == 0
            with np.errstate(all="ignore"):
                newton = np.maximum(1.25 * np.abs(fx) / self.slope[rows], 1e-6 * x)
            newton = np.where(np.isfinite(newton) & (self.slope[rows] > 0), newton, _PROBE * x)
            offset = np.where(first, newton, self.step[rows] * x)
            self.step[rows] = np.where(first, self.step[rows], 4.0 * self.step[rows])
            self.count[rows] += 1
            upward = np.isnan(self.f_top[rows])
            self.x[rows] = np.where(upward, np.minimum(x + offset, self.hi[rows]), np.maximum(x - offset, 0.1 * x))

    def brackets(self) -> tuple[np.ndarray, ...]:
        """lo, top, f(lo), f(top); where f does not cross 0 in [0, hi], lo = top = hi (`increasing_root` then
        ends there). Elements never probed above their root are settled by f(hi)."""
        left = np.flatnonzero(self.open & np.isnan(self.f_top) & (self.lo < self.hi))
        if left.size:
            self.f_top[left] = self.f(self.hi[left], left)
        none = ~(self.f_top >= 0.0) | ~(self.f_lo < 0.0)
        self.lo[none] = self.top[none] = self.hi[none]
        return self.lo, self.top, self.f_lo, self.f_top


def increasing_root(f: Excess, lo: np.ndarray, hi: np.ndarray, f_lo: np.ndarray | None = None,
                    f_hi: np.ndarray | None = None) -> np.ndarray:
    """Per element of the 1-D brackets [lo, hi], where the increasing `f` crosses 0 (f(lo) < 0 <= f(hi)): the
    estimate once it moves by no more than _ROOT_TOLERANCE of hi - lo. `f(x, index)` evaluates the elements
    `index` (an integer array) at x; `f_lo`, `f_hi`, if given, are f at the ends.

    Regula falsi with the Anderson-Bjorck step (1973; never less than the Illinois step of Dowell & Jarratt
    1971), which converges superlinearly and never leaves the bracket; each element is evaluated only until it
    has converged: on the power curves, from the probed brackets, in three steps. Where the step is not finite
    or outside the bracket, a bisection step is taken instead. Where f does not cross 0 in [lo, hi], an end of
    it (which, unspecified)."""
    everything = np.arange(lo.size)
    lo, hi = lo.astype(np.float64), hi.astype(np.float64)
    f_lo = f(lo, everything) if f_lo is None else np.array(f_lo, np.float64)
    f_hi = f(hi, everything) if f_hi is None else np.array(f_hi, np.float64)
    tolerance = _ROOT_TOLERANCE * (hi - lo)
    side = np.zeros(lo.shape, dtype=np.int8)  # which end moved last: -1 lo, +1 hi
    x = hi.copy()
    active = everything[(f_lo < 0.0) & (f_hi >= 0.0)]  # one of sign, or NaN: not searched
    for _ in range(_ROOT_STEPS):
        if not active.size:
            break
        a_lo, a_hi, a_flo, a_fhi = lo[active], hi[active], f_lo[active], f_hi[active]
        with np.errstate(all="ignore"):
            secant = a_hi - a_fhi * (a_hi - a_lo) / (a_fhi - a_flo)
        new = np.where(np.isfinite(secant) & (secant >= a_lo) & (secant <= a_hi), secant, 0.5 * (a_lo + a_hi))
        moving = np.abs(new - x[active]) > tolerance[active]
        x[active] = new
        active, new = active[moving], new[moving]
        if not active.size:
            break
        fx = f(new, active)
        up = fx >= 0.0  # the root is at or below x
        s = side[active]
        # Anderson-Bjorck: the end kept a second time in a row has its value scaled by 1 - f(new) / f(the end
        # replaced), by a half at least (the Illinois step), so that the next step moves it.
        with np.errstate(all="ignore"):
            m = 1.0 - fx / np.where(up, f_hi[active], f_lo[active])
        m = np.where(m > 0.5, m, 0.5)
        f_lo[active] = np.where(up, np.where(s == 1, m * f_lo[active], f_lo[active]), fx)
        f_hi[active] = np.where(up, fx, np.where(s == -1, m * f_hi[active], f_hi[active]))
        hi[active] = np.where(up, new, hi[active])
        lo[active] = np.where(up, lo[active], new)
        side[active] = np.where(up, 1, -1)
    return x
