"""Welch's t-test on batch statistics, vectorised over every pixel, tile or channel at once."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats as sps

from harness.stats import ROUNDING_TOLERANCE


@dataclass
class BatchStats:
    """Means over K independent batches and the variance of those means, per element."""

    mean: np.ndarray
    var_of_mean: np.ndarray
    k: int

    @classmethod
    def of(cls, batches: np.ndarray) -> "BatchStats":
        """From (K, ...) batch values."""
        b = np.asarray(batches, np.float64)
        return cls(b.mean(axis=0), b.var(axis=0, ddof=1) / b.shape[0], b.shape[0])


def welch_p_values(a: BatchStats, b: BatchStats, scale: float = 0.0,
                   rounding: float = ROUNDING_TOLERANCE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two-sided p-values of Welch's t-test between two sets of batch statistics.

    Returns (p, t, standard error). The standard error has a floor of `rounding`
    times the values' magnitude plus `scale` (the image's typical magnitude), so
    two engines that agree to float32 rounding on a noiseless pixel (a flat normal,
    a component that is 0 in one and 3e-8 in the other) are not told apart; where
    both sides are constant and equal the p-value is 1. Where any input (either
    mean or variance, or `scale`) is NaN or infinite, t and p are NaN: such a pixel is no
    evidence of agreement.
    """
    va, vb = a.var_of_mean, b.var_of_mean
    floor = rounding * (0.5 * (np.abs(a.mean) + np.abs(b.mean)) + scale)
    finite = np.isfinite(a.mean) & np.isfinite(b.mean) & np.isfinite(va) & np.isfinite(vb) & np.isfinite(floor)
    with np.errstate(invalid="ignore", over="ignore"):
        se = np.sqrt(va + vb + floor**2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = np.where(finite, np.where(se > 0, (a.mean - b.mean) / se, 0.0), np.nan)
        # Welch-Satterthwaite degrees of freedom; the pooled count where both variances vanish.
        dof_den = va**2 / (a.k - 1) + vb**2 / (b.k - 1)
        dof = np.where(dof_den > 0, (va + vb) ** 2 / dof_den, a.k + b.k - 2.0)
    dof = np.clip(np.nan_to_num(dof, nan=a.k + b.k - 2.0), 1.0, None)
    p = 2.0 * sps.t.sf(np.abs(t), dof)
    return p, t, se


def critical_t(level: float, dof: float) -> float:
    """|t| beyond which a two-sided test at `level` rejects."""
    return float(sps.t.isf(level / 2.0, dof))
