"""The per-test level that gives a family of Welch tests its stated false-alarm rate.

Šidák's split, level_family = 1 - (1 - level)^N, holds for N independent tests that each reject a
correct renderer at exactly `level`. Two things in an image make that count wrong, both towards a
test that almost never fires:

- Not every element can reject. A pixel without noise on either side has t = 0 whenever the engines
  agree; a pixel whose noise is below the rounding floor of the standard error rejects far less often
  than its p-value's level says. Each element is counted by its own null rejection probability at the
  candidate level (`element_rates`), 0 for the noiseless ones.
- The three colour channels of one element are nearly the same test (a white light on coloured walls
  gives channel correlations of 0.95 to 1). The chance that any of the three rejects is computed for
  Gaussian statistics with the channels' mean correlation (`channel_union`), between 1x and 3x one
  channel's.

`family_level` then solves 1 - prod_i (1 - r_i(level)) = level_family for the common p-value level.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from harness.statistics.distributions import norm_isf, norm_pdf, norm_sf, t_isf, t_sf

#: Channel correlations below 1 are clipped here: near 1 the integrand's inner normal has no width.
MAX_CORRELATION = 0.999
#: Statistics beyond this |t| are clipped before their correlation is taken, so a few biased elements
#: (the alternative) do not decide it.
CORRELATION_CLIP = 4.0
#: Tests whose rounding floor matters are summed over a systematic sample of at most this many.
SAMPLED = 2048
#: The integration grid of `channel_union`, symmetric about 0 (the lower tail is then the upper one reversed),
#: and its trapezoid rule's weights times the normal density.
_GRID = np.concatenate([-np.linspace(9.0, 0.0, 1801)[:-1], np.linspace(0.0, 9.0, 1801)])
_WEIGHTS = norm_pdf(_GRID) * (np.r_[np.diff(_GRID), 0.0] + np.r_[0.0, np.diff(_GRID)]) / 2.0


def channel_correlation(t: np.ndarray, live: np.ndarray) -> float:
    """Mean correlation between the channels of (..., C) t statistics over the `live` elements (all
    channels finite and noisy), at the low end of its uncertainty; 1 where the channels are identical,
    else 0 where there are fewer than 10 such elements or one channel."""
    if t.ndim < 2 or t.shape[-1] < 2:
        return 0.0
    rows = np.clip(t[live], -CORRELATION_CLIP, CORRELATION_CLIP)
    if rows.size and np.array_equal(rows, np.repeat(rows[:, :1], rows.shape[1], axis=1)):
        return 1.0  # identical channels, however few
    if rows.shape[0] < 10:
        return 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = np.corrcoef(rows, rowvar=False)
    off = corr[~np.eye(corr.shape[0], dtype=bool)]
    off = off[np.isfinite(off)]
    if not off.size:
        return 0.0
    # The lower end of its ~97.5 % interval (Fisher's z): a correlation overstated by chance would raise the
    # level; understated, it only makes the test a little more conservative.
    r = float(np.clip(off.mean(), 0.0, 1.0 - 1e-12))
    return float(max(0.0, np.tanh(np.arctanh(r) - 2.0 / np.sqrt(rows.shape[0] - 3))))


@lru_cache(maxsize=1024)  # asked again at the levels found, for the power figures
def channel_union(level: float, channels: int, rho: float) -> float:
    """P(any of `channels` equicorrelated standard normals (correlation rho) exceeds the two-sided
    critical value of `level`), divided by `level`: the effective number of channels, in [1, channels]."""
    if channels <= 1 or rho <= 0.0:
        return float(channels)
    if rho >= 1.0 - 1e-9:  # identical channels (a grey image): one test
        return 1.0
    rho = min(rho, MAX_CORRELATION)
    c = norm_isf(level / 2.0)
    root, width = np.sqrt(rho), np.sqrt(1.0 - rho)
    upper = norm_sf((c - root * _GRID) / width)
    tail = upper + upper[::-1]  # P(X > c) + P(X < -c) given the shared part at g: the second is the first at -g
    with np.errstate(divide="ignore"):  # a tail of 1 (far out on the grid) is log1p(-1) = -inf: union 1
        union = -np.expm1(channels * np.log1p(-np.minimum(tail, 1.0)))
    any_channel = float(_WEIGHTS @ union)
    return float(np.clip(any_channel / level, 1.0, channels))


def element_rates(level: float, dof: np.ndarray, inflation: np.ndarray,
                  distinct: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Null rejection probability of each test at p-value `level`: its statistic is t(dof) shrunk by
    `inflation` = se / noise-only se >= 1 (the rounding floor); inf inflation (no noise) gives 0.
    `distinct`: np.unique(dof, return_inverse=True), for a caller that asks at many levels (the critical
    values are then computed once per distinct dof: moderated tests share a few)."""
    if distinct is None:
        crit = t_isf(level / 2.0, dof)
    else:
        crit = t_isf(level / 2.0, distinct[0])[distinct[1]]
    with np.errstate(invalid="ignore", over="ignore"):
        rate = 2.0 * t_sf(crit * inflation, dof)
    return np.where(np.isfinite(inflation), rate, 0.0)


def family_level(level_family: float, dof: np.ndarray, inflation: np.ndarray, rho: float = 0.0) -> float:
    """The p-value level at which the (..., C) tests with `dof` and `inflation` (see `element_rates`)
    reject a correct renderer with probability `level_family`, their C channels correlated by `rho`.

    Never below Šidák's level for all tests (the count it replaces), never above `level_family`."""
    dof, inflation = np.broadcast_arrays(np.asarray(dof, np.float64), np.asarray(inflation, np.float64))
    channels = dof.shape[-1] if dof.ndim >= 1 else 1
    total = max(dof.size, 1)
    lowest = 1.0 - (1.0 - level_family) ** (1.0 / total)
    live = np.isfinite(inflation)
    # Tests the floor does not touch reject at exactly the level; the others are summed by a systematic
    # sample of at most SAMPLED tests in order of inflation (the rate is smooth and monotone in it).
    exact = live & (inflation <= 1.0 + 1e-9)
    floored = live & ~exact
    # Inflations above 1 order as their bit patterns do, which sort faster.
    order = np.argsort(inflation[floored].view(np.int64), kind="stable")
    stride = max(1, -(-order.size // SAMPLED))
    pick = order[stride // 2::stride]
    dof_s, inflation_s = dof[floored][pick], inflation[floored][pick]
    weight = order.size / max(pick.size, 1)
    n_exact = int(np.count_nonzero(exact))
    if n_exact + order.size == 0:
        return level_family
    distinct = np.unique(dof_s, return_inverse=True)
    known: dict[float, float] = {}

    def hazard(log_level: float) -> float:
        """-log P(no test rejects) at exp(log_level); each level evaluated once (brentq asks for its ends again)."""
        if log_level not in known:
            level = float(np.exp(log_level))
            share = channel_union(level, channels, rho) / channels
            rates = np.minimum(element_rates(level, dof_s, inflation_s, distinct) * share, 1.0)
            with np.errstate(divide="ignore"):
                known[log_level] = -(n_exact * np.log1p(-min(level * share, 1.0)) + weight * np.sum(np.log1p(-rates)))
        return known[log_level]

    target = -np.log1p(-level_family)
    lo, hi = np.log(lowest), np.log(level_family)
    if hazard(hi) <= target:
        return level_family
    if hazard(lo) >= target:
        return lowest

    def excess(log_level: float) -> float:
        # log hazard against log level is nearly a straight line (slope 1 for tests at their level), so
        # brentq's interpolation lands close: half the steps of the family rate's excess itself.
        return float(np.log(max(hazard(log_level), 1e-300)) - np.log(target))

    return float(np.exp(brentq(excess, lo, hi, xtol=1e-9)))
