"""Welch's t-test on batch statistics, vectorised over every pixel, tile or channel at once, and the
empirical-Bayes moderation of their variances (Smyth 2004) over a neighbourhood."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import uniform_filter
from scipy.optimize import brentq
from scipy.special import polygamma

from harness.statistics.distributions import t_isf, t_sf
from harness.statistics.constants import MISSED_CONTRIBUTION, MODERATION_WINDOW, ROUNDING_TOLERANCE


@dataclass
class BatchStats:
    """Means over K independent batches and the variance of those means, per element.

    `dof` is the degrees of freedom of each variance: K - 1 when None (a plain sample
    variance), more once moderated (`moderate`)."""

    mean: np.ndarray
    var_of_mean: np.ndarray
    k: int
    dof: np.ndarray | None = None

    @classmethod
    def of(cls, batches: np.ndarray) -> "BatchStats":
        """From (K, ...) batch values."""
        b = np.asarray(batches, np.float64)
        return cls(b.mean(axis=0), b.var(axis=0, ddof=1) / b.shape[0], b.shape[0])

    @property
    def var_dof(self) -> np.ndarray | float:
        """Degrees of freedom of `var_of_mean`, per element (K - 1 unless moderated)."""
        return float(self.k - 1) if self.dof is None else self.dof


def rounding_floor(values: np.ndarray, at: np.ndarray | None = None) -> np.ndarray:
    """How far float rounding may move a value: ROUNDING_TOLERANCE (|value| + the mean magnitude of the finite
    `values`), at each of `values`, or at `at` where given (a median, say)."""
    v = np.asarray(values, np.float64)
    finite = np.abs(v[np.isfinite(v)])
    return ROUNDING_TOLERANCE * (np.abs(v if at is None else at) + (float(finite.mean()) if finite.size else 0.0))


def beyond_rounding(stats: BatchStats) -> np.ndarray:
    """Elements whose K batch means spread beyond float rounding of the values: (K - 1) var_of_mean (the sum
    of squared deviations over K) above the squared floor ROUNDING_TOLERANCE (|mean| + the mean magnitude of
    the finite elements). A noiseless estimator summed in another order, or rounded one way in one engine and
    another way in the other, has no variance."""
    floor = rounding_floor(stats.mean)
    with np.errstate(invalid="ignore", over="ignore"):
        return (stats.k - 1) * np.asarray(stats.var_of_mean, np.float64) > floor * floor


def _trigamma(x):
    return polygamma(1, x)


def prior_dof(log_ratio: np.ndarray, dof: float, cap: float) -> float:
    """Method-of-moments prior degrees of freedom d0 (Smyth 2004): the spread of log(s^2 / s0^2) beyond
    what sampling with `dof` degrees of freedom explains is trigamma(d0 / 2); capped at `cap`, 0 when
    fewer than 10 ratios are given."""
    if log_ratio.size < 10:
        return 0.0
    excess = float(np.var(log_ratio)) - float(_trigamma(dof / 2.0))
    if excess <= _trigamma(cap / 2.0):
        return float(cap)
    return float(brentq(lambda d0: _trigamma(d0 / 2.0) - excess, 1e-6, cap))


def _neighbours(masks: np.ndarray, window: int) -> np.ndarray:
    """For (M, H, W, C) boolean masks, how many of each element's `window` x `window` neighbours (same channel,
    itself excluded, the edges repeated as uniform_filter's mode "nearest" does) are set: exact integer sums,
    in small integers (a box filter of floats per mask costs several times as much)."""
    before, after = window // 2, (window - 1) // 2
    small = np.uint8 if window * window < 256 else np.int32
    padded = np.pad(masks.astype(small), ((0, 0), (before, after), (before, after), (0, 0)), mode="edge")
    h, w = masks.shape[1:3]
    rows = sum(padded[:, k:k + h] for k in range(window))
    return (sum(rows[:, :, k:k + w] for k in range(window)) - masks).astype(np.float64)


def moderate(stats: BatchStats, window: int = MODERATION_WINDOW) -> BatchStats:
    """Variances of (H, W, C) statistics moderated towards their neighbours' (Smyth 2004, limma).

    The prior of an element comes from the mean variance m of the finite elements in its `window` x
    `window` neighbourhood (same channel, the element itself excluded); its weight d0 (prior degrees of
    freedom) is estimated once per image from how much the variances scatter about m. Under Smyth's
    prior, sigma^2 ~ s0^2 d0 / chi2(d0), a mean of variances estimates E[sigma^2] = s0^2 d0 / (d0 - 2),
    not the scale s0^2, so s0^2 = m (d0 - 2) / d0; taking m itself made the pixel test reject null
    Gaussian pairs at a quarter of its level (0.028 against 0.112). Where d0 <= 2 that mean does not
    exist and m is kept (on the safe side: larger). The moderated variance (d0 s0^2 + d s^2) / (d0 + d)
    has d0 + d degrees of freedom (d = K - 1). Where a contribution
    is rare and all K batches miss it (s^2 = 0), the neighbours supply the variance; where the variance
    field is smooth, d0 is large and the estimate nearly exact. Elements with a neighbour of zero
    variance (at an edge of the noise field), and non-finite ones, keep their own variance and K - 1
    degrees of freedom.
    """
    v = np.asarray(stats.var_of_mean, np.float64)
    d = float(stats.k - 1)
    if v.ndim != 3 or min(v.shape[:2]) < 2:
        return stats
    finite = np.isfinite(v)
    clean = np.where(finite, v, 0.0)
    size = (window, window, 1)
    n = window * window
    with np.errstate(invalid="ignore", over="ignore"):
        total = uniform_filter(clean, size=size, mode="nearest") * n - clean
        # Neighbours that are finite, that have a variance at all, and that have none (`silent`).
        positive = clean > 0
        silent = finite & ~positive
        count, varied, quiet = _neighbours(np.stack([finite, positive, silent]), window)
        prior = np.where((count > 0.5) & (varied > 0.5), total / np.maximum(count, 1.0), 0.0)
        # A neighbour without noise (the background beside an edge, a lit patch with no variance) marks
        # where the variance field is not exchangeable: there the neighbours' mean says nothing of the
        # element's own, and granting it their degrees of freedom made a binomial edge pixel, whose 8
        # batches happened to agree, reject at p = 2e-10 (far_from_origin, ao).
    usable = finite & (prior > 0) & np.isfinite(prior) & (quiet < 0.5)
    observed = usable & (v > 0)
    d0 = prior_dof(np.log(v[observed] / prior[observed]), d, (n - 1) * d)
    if d0 <= 0.0:
        return stats
    scale = prior * ((d0 - 2.0) / d0 if d0 > 2.0 else 1.0)
    moderated = np.where(usable, (d0 * np.where(usable, scale, 0.0) + d * clean) / (d0 + d), v)
    dof = np.where(usable, d + d0, d)
    return BatchStats(stats.mean, moderated, stats.k, dof)


def sample_floor(a: BatchStats, b: BatchStats, samples_a: int | None, samples_b: int | None,
                 raw_a: BatchStats | None = None, raw_b: BatchStats | None = None) -> tuple[BatchStats, BatchStats]:
    """The variance of the mean of the side with fewer samples, where it is far below what the other side's
    implies for its sample count, replaced by that prediction.

    With n samples per batch and K batches an independent-sample estimate has variance sigma^2 / (K n),
    so under the null the better-sampled side predicts the other's. Where a contribution is rare (a
    shadow sliver one sample in 30 hits) all K batches of the smaller side can miss it and agree to
    1e-4 while their mean is 2 % off, and no neighbour knows: the other side, with more samples, has
    seen it. Only a variance below MISSED_CONTRIBUTION times the prediction is replaced (a sample
    variance with 7 degrees of freedom falls there by chance with probability 7e-4), because taking the
    larger of two estimates everywhere makes the extreme-level pixel tests far too conservative. A
    stratified sampler beats sigma^2 / n, so a replaced variance is then larger than needed, never
    smaller. Replaced elements take the other side's degrees of freedom. `raw_a` and `raw_b`, when `a`
    and `b` are moderated, are their variances before: a missed contribution is judged on the element's
    own batches, which its neighbours' variances would hide. Unchanged when a count is unknown (None) or
    both sides hold as many samples."""
    if samples_a is None or samples_b is None or a.k * samples_a == b.k * samples_b:
        return a, b
    if a.k * samples_a > b.k * samples_b:
        floored_b, floored_a = sample_floor(b, a, samples_b, samples_a, raw_b, raw_a)
        return floored_a, floored_b
    floor = b.var_of_mean * (b.k * samples_b) / (a.k * samples_a)
    own = (a if raw_a is None else raw_a).var_of_mean
    with np.errstate(invalid="ignore"):
        use = (MISSED_CONTRIBUTION * floor > own) & (floor > a.var_of_mean)
    dof = np.where(use, np.broadcast_to(b.var_dof, use.shape), np.broadcast_to(a.var_dof, use.shape))
    return BatchStats(a.mean, np.where(use, floor, a.var_of_mean), a.k, dof), b


def welch_dof(a: BatchStats, b: BatchStats) -> np.ndarray:
    """Welch-Satterthwaite degrees of freedom; the summed variance dofs where both variances vanish."""
    va, vb = a.var_of_mean, b.var_of_mean
    da, db = a.var_dof, b.var_dof
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        dof_den = va**2 / da + vb**2 / db
        dof = np.where(dof_den > 0, (va + vb) ** 2 / dof_den, da + db)
    return np.clip(np.nan_to_num(np.asarray(dof, np.float64), nan=a.k + b.k - 2.0), 1.0, None)


def welch_p_values(a: BatchStats, b: BatchStats, scale: float = 0.0,
                   rounding: float = ROUNDING_TOLERANCE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two-sided p-values of Welch's t-test between two sets of batch statistics.

    Returns (p, t, standard error). The standard error has a floor of `rounding`
    times the values' magnitude plus `scale` (the image's typical magnitude), so
    two engines that agree to float32 rounding on a noiseless pixel (a flat normal,
    a component that is 0 in one and 3e-8 in the other) are not told apart; where
    both sides are constant and equal the p-value is 1. Where any input (either
    mean or variance, or `scale`) is NaN or infinite, t and p are NaN: such a pixel is no
    evidence of agreement. Moderated variances (`moderate`) bring their own degrees of freedom.
    """
    va, vb = a.var_of_mean, b.var_of_mean
    floor = rounding * (0.5 * (np.abs(a.mean) + np.abs(b.mean)) + scale)
    finite = np.isfinite(a.mean) & np.isfinite(b.mean) & np.isfinite(va) & np.isfinite(vb) & np.isfinite(floor)
    with np.errstate(invalid="ignore", over="ignore"):
        se = np.sqrt(va + vb + floor**2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = np.where(finite, np.where(se > 0, (a.mean - b.mean) / se, 0.0), np.nan)
    p = 2.0 * t_sf(np.abs(t), welch_dof(a, b))
    return p, t, se


def critical_t(level: float, dof: float | np.ndarray) -> float | np.ndarray:
    """|t| beyond which a two-sided test at `level` rejects."""
    out = t_isf(level / 2.0, dof)
    return float(out) if np.ndim(out) == 0 else out
