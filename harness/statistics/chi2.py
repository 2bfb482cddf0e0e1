"""Chi-square tests on histograms: goodness of fit to expected counts, and homogeneity of two samples.

Each test also comes vectorised over replications (`*_batch`), for power simulations. A test that cannot
judge its counts (fewer than two bins once sparse cells are pooled, an empty histogram, counts that are not
finite) says so and why, and its p-value is NaN: never a p-value that passes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.statistics.constants import MIN_EXPECTED
from harness.statistics.distributions import chi2_sf


@dataclass
class Chi2Result:
    """A chi-square statistic with its degrees of freedom and p-value."""

    statistic: float
    dof: int
    p_value: float
    #: Cells merged into one bin because their expected count was below MIN_EXPECTED.
    pooled_cells: int
    #: Why the counts could not be judged (then statistic and p_value are NaN); None for a test that judged.
    not_judged: str | None = None


@dataclass
class Chi2Batch:
    """Chi-square statistics of many replications of one test, their degrees of freedom and p-values."""

    statistics: np.ndarray
    dofs: np.ndarray
    p_values: np.ndarray
    #: Cells merged into one bin because their expected count was below MIN_EXPECTED (per replication).
    pooled_cells: np.ndarray


def _pool(observed: np.ndarray, expected: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Merge all cells expecting fewer than MIN_EXPECTED into one bin (kept only if it is large enough).

    observed: (replications, cells); expected: (cells,). Returns the pooled observed and expected bins.
    """
    low = expected < MIN_EXPECTED
    obs, exp = observed[:, ~low], expected[~low]
    pooled_obs, pooled_exp = observed[:, low].sum(axis=1), expected[low].sum()
    if pooled_exp >= MIN_EXPECTED:
        obs = np.concatenate([obs, pooled_obs[:, None]], axis=1)
        exp = np.append(exp, pooled_exp)
    elif low.any() and len(exp):
        # Too little to stand alone: fold it into the smallest regular bin.
        i = int(np.argmin(exp))
        obs, exp = obs.copy(), exp.copy()
        obs[:, i] += pooled_obs
        exp[i] += pooled_exp
    return obs, exp, int(low.sum())


def goodness_of_fit_batch(observed: np.ndarray, expected: np.ndarray) -> Chi2Batch:
    """Pearson's test of each row of observed counts (replications, cells) against one row of expected counts.

    As `goodness_of_fit`, vectorised over replications (power simulations); rows it cannot judge get NaN.
    """
    obs, exp, pooled = _pool(np.asarray(observed, dtype=float), np.ravel(expected).astype(float))
    n = len(obs)
    if len(exp) < 2:
        return Chi2Batch(np.full(n, np.nan), np.zeros(n, int), np.full(n, np.nan), np.full(n, pooled))
    statistics = np.sum((obs - exp) ** 2 / exp, axis=1)
    dof = len(exp) - 1
    return Chi2Batch(statistics, np.full(n, dof), chi2_sf(statistics, dof), np.full(n, pooled))


def _unusable(*counts: np.ndarray) -> str | None:
    """Why these counts cannot be tested (NaN, infinite or negative ones), or None."""
    if not all(np.all(np.isfinite(c)) for c in counts):
        return "counts that are NaN or infinite"
    if any(np.any(c < 0) for c in counts):
        return "negative counts"
    return None


def _not_judged(reason: str, pooled: int = 0) -> Chi2Result:
    return Chi2Result(float("nan"), 0, float("nan"), pooled, reason)


def goodness_of_fit(observed: np.ndarray, expected: np.ndarray) -> Chi2Result:
    """Pearson's test of observed counts against expected counts (same shape, any dimension).

    The expected counts are not rescaled to the observed total: a pdf that does
    not integrate to one fails here as it should. Not judged (see Chi2Result) when fewer than two bins
    expect MIN_EXPECTED once the sparse cells are pooled: a pdf of integral 1e-5 expects 10 of 10^6 samples.
    """
    observed, expected = np.ravel(observed).astype(float), np.ravel(expected).astype(float)
    reason = _unusable(observed, expected)
    if reason:
        return _not_judged(reason)
    res = goodness_of_fit_batch(observed[None, :], expected)
    if res.dofs[0] < 1:
        return _not_judged(f"fewer than two cells expect {MIN_EXPECTED:g} samples or more ({expected.sum():.3g} "
                           f"expected in all, {observed.sum():.0f} observed)", int(res.pooled_cells[0]))
    return Chi2Result(float(res.statistics[0]), int(res.dofs[0]), float(res.p_values[0]), int(res.pooled_cells[0]))


def homogeneity_batch(counts_a: np.ndarray, counts_b: np.ndarray) -> Chi2Batch:
    """Test each pair of rows of counts_a and counts_b (replications, cells) for one common distribution.

    As `homogeneity` (the 2 x k contingency table without continuity correction), vectorised over replications;
    rows it cannot judge (an empty side, every count in one cell) get NaN.
    """
    a, b = np.atleast_2d(np.asarray(counts_a, dtype=float)), np.atleast_2d(np.asarray(counts_b, dtype=float))
    total_a, total_b = a.sum(axis=1, keepdims=True), b.sum(axis=1, keepdims=True)
    total = total_a + total_b
    share = total_a / np.where(total > 0, total, 1.0)
    low = np.minimum(share, 1.0 - share) * (a + b) < MIN_EXPECTED
    col = np.where(low, 0.0, a + b)
    # Regular columns, then one pooled column of the low cells; columns with no counts are dropped.
    cols = np.concatenate([col, np.where(low, a + b, 0.0).sum(axis=1, keepdims=True)], axis=1)
    col_a = np.concatenate([np.where(low, 0.0, a), np.where(low, a, 0.0).sum(axis=1, keepdims=True)], axis=1)
    used = cols > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        d = col_a - total_a * cols / total
        terms = np.where(used, d * d * total * total / (total_a * total_b * np.where(used, cols, 1.0)), 0.0)
    statistics = np.nan_to_num(terms.sum(axis=1))
    dofs = used.sum(axis=1) - 1
    ok = (dofs >= 1) & (total_a[:, 0] > 0) & (total_b[:, 0] > 0)
    statistics = np.where(ok, statistics, np.nan)
    p_values = np.where(ok, chi2_sf(statistics, np.maximum(dofs, 1)), np.nan)
    return Chi2Batch(statistics, np.where(ok, dofs, 0), p_values, low.sum(axis=1))


def homogeneity(counts_a: np.ndarray, counts_b: np.ndarray) -> Chi2Result:
    """Test whether two histograms come from the same distribution (2 x k contingency table).

    Cells whose expected count under the pooled distribution falls below
    MIN_EXPECTED in either row are merged first. Not judged (see Chi2Result) when a histogram is empty or
    all counts of both fall in one bin.
    """
    a, b = np.ravel(counts_a).astype(float), np.ravel(counts_b).astype(float)
    reason = _unusable(a, b)
    if reason:
        return _not_judged(reason)
    if not (a.sum() > 0 and b.sum() > 0):
        return _not_judged(f"an empty histogram ({a.sum():.0f} and {b.sum():.0f} counts)")
    res = homogeneity_batch(a[None, :], b[None, :])
    if res.dofs[0] < 1:
        return _not_judged("every count of both histograms in one bin", int(res.pooled_cells[0]))
    return Chi2Result(float(res.statistics[0]), int(res.dofs[0]), float(res.p_values[0]), int(res.pooled_cells[0]))
