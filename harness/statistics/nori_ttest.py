"""Nori's Student's t-test of a Monte Carlo mean against a stated value (its hypothesis::students_t_test): the
statistic |mean - reference| sqrt(n / variance), the variance floored at 1e-5, two-sided against Student's t
with n - 1 degrees of freedom, or with those of the variance's estimate where it comes from fewer values (batch
means). The level is the caller's (Nori's: Sidak-corrected over the file's tests)."""
from __future__ import annotations

import numpy as np

from harness.statistics.distributions import t_sf

#: The smallest variance Nori divides by (a noiseless estimate still gets a finite statistic).
VARIANCE_FLOOR = 1e-5


def students_t_test(mean: float, variance: float, reference: float, samples: int, level: float,
                    dof: int | None = None) -> tuple[bool, float | None, str]:
    """(passed, p-value, Nori's message) of `samples` values of this mean and per-value variance; `dof`: the
    variance estimate's degrees of freedom (None: samples - 1, Nori's, for a variance of the values themselves)."""
    statistic = abs(mean - reference) * np.sqrt(samples / max(variance, VARIANCE_FLOOR))
    p = float(2 * t_sf(statistic, samples - 1 if dof is None else dof))
    passed = bool(np.isfinite(p) and p >= level)
    return passed, p, (f"mean {mean:.6g} (reference {reference:g}), variance {variance:.4g}, t = {statistic:.4g}, "
                       f"p = {p:.4g} {'>=' if passed else '<'} level {level:.4g}")
