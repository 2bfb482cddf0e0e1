"""The bias a comparison finds half of the time: per element of (..., C) statistics, the relative bias at which
the Welch test rejects in at least one channel with probability IMAGE_POWER_TARGET (the noncentral t), found
by a root search that evaluates each element only until its estimate settles."""
from __future__ import annotations

from typing import Callable

import numpy as np

from harness.statistics.constants import IMAGE_POWER_TARGET
from harness.statistics.distributions import nct_cdf, nct_sf
from harness.statistics.family_level import channel_union
from harness.statistics.welch import BatchStats, critical_t

#: The root search of `increasing_root` (regula falsi, Illinois) stops when no element's estimate moves by
#: more than this, relative to its first bracket, or after this many steps.
_ROOT_TOLERANCE = 1e-10
_ROOT_STEPS = 100


def half_power_bias(reference: BatchStats, se: np.ndarray, dof: np.ndarray, level: float,
                     rho: float, power: float = IMAGE_POWER_TARGET) -> np.ndarray:
    """Per element of (..., C) statistics: the relative bias b (the test scaled by 1 + b) that makes the
    test at `level` reject in at least one of the C channels with probability `power` (IMAGE_POWER_TARGET,
    a half, unless given).

    Channel c's t is noncentral with noncentrality b |mean_c| / se_c and the Welch degrees of freedom.
    Channels correlated by `rho` count as `channel_union` of them at the null does: P(any) is
    1 - prod_c (1 - power_c)^(union / C), exact for independent (rho = 0) and for identical (rho = 1)
    channels. Infinite where no channel has a non-zero mean."""
    scale = np.where(np.isfinite(reference.mean) & (se > 0), np.abs(reference.mean) / np.where(se > 0, se, 1.0), 0.0)
    scale = np.atleast_2d(scale)
    dof = np.broadcast_to(np.atleast_2d(dof), scale.shape)
    crit = critical_t(level, dof)
    best = scale.max(axis=-1, keepdims=True)
    share = channel_union(level, scale.shape[-1], rho) / scale.shape[-1]
    live = best[..., 0] > 0
    # Searched as (elements, channels) rows, each row's channels together.
    rows = tuple(np.reshape(r, (-1, scale.shape[-1])) for r in (scale, crit, dof))

    def excess(b: np.ndarray, index: np.ndarray) -> np.ndarray:
        """P(some channel rejects at bias b) - IMAGE_POWER_TARGET for the rows `index`: increasing in b."""
        row_scale, row_crit, row_dof = (r[index] for r in rows)
        nc = b[:, None] * row_scale
        with np.errstate(all="ignore"):  # scipy's nct returns NaN for some far tails: 0 below, a step above
            upper, lower = nct_sf(row_crit, row_dof, nc), nct_cdf(-row_crit, row_dof, nc)
        channel = np.where(np.isnan(upper), (nc > row_crit).astype(float), upper) + np.nan_to_num(lower, nan=0.0)
        with np.errstate(divide="ignore"):
            missed = np.exp(share * np.sum(np.log1p(-np.minimum(channel, 1.0)), axis=-1))
        return (1.0 - missed) - power

    hi = np.where(best > 0, (2.0 * crit.max(axis=-1, keepdims=True) + 8.0) / np.where(best > 0, best, 1.0), 1.0)
    root = increasing_root(excess, np.zeros(hi.size), hi.reshape(-1)).reshape(live.shape)
    return np.where(live, root, np.inf)


def increasing_root(f: Callable[[np.ndarray, np.ndarray], np.ndarray], lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Per element of the 1-D brackets [lo, hi], where the increasing `f` crosses 0 (f(lo) < 0 <= f(hi)): the
    estimate once it moves by no more than _ROOT_TOLERANCE of hi - lo. `f(x, index)` evaluates the elements
    `index` (an integer array) at x.

    Regula falsi with the Illinois step (Dowell & Jarratt 1971), which converges superlinearly and never
    leaves the bracket; each element is evaluated only until it has converged, on the power curves in about a
    third of a bisection's 33 steps. Where the step is not finite or not inside the bracket, a bisection step
    is taken instead. Where f does not cross 0 in [lo, hi], an end of it (which, unspecified)."""
    everything = np.arange(lo.size)
    lo, hi = lo.astype(np.float64), hi.astype(np.float64)
    f_lo, f_hi = f(lo, everything), f(hi, everything)
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
        new = np.where(np.isfinite(secant) & (secant > a_lo) & (secant < a_hi), secant, 0.5 * (a_lo + a_hi))
        moving = np.abs(new - x[active]) > tolerance[active]
        x[active] = new
        active, new = active[moving], new[moving]
        if not active.size:
            break
        fx = f(new, active)
        up = fx >= 0.0  # the root is at or below x
        s = side[active]
        # Illinois: the end kept a second time in a row has its value halved, so that the next step moves it.
        f_lo[active] = np.where(up, np.where(s == 1, 0.5 * f_lo[active], f_lo[active]), fx)
        f_hi[active] = np.where(up, fx, np.where(s == -1, 0.5 * f_hi[active], f_hi[active]))
        hi[active] = np.where(up, new, hi[active])
        lo[active] = np.where(up, lo[active], new)
        side[active] = np.where(up, 1, -1)
    return x
