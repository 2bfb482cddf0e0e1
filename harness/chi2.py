"""Chi-square tests on histograms: goodness of fit to expected counts, and homogeneity of two samples."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats as sps

from harness.stats import MIN_EXPECTED


@dataclass
class Chi2Result:
    """A chi-square statistic with its degrees of freedom and p-value."""

    statistic: float
    dof: int
    p_value: float
    #: Cells merged into one bin because their expected count was below MIN_EXPECTED.
    pooled_cells: int


def _pool(observed: np.ndarray, expected: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Merge all cells expecting fewer than MIN_EXPECTED into one bin (kept only if it is large enough)."""
    low = expected < MIN_EXPECTED
    obs, exp = list(observed[~low]), list(expected[~low])
    pooled_obs, pooled_exp = observed[low].sum(), expected[low].sum()
    if pooled_exp >= MIN_EXPECTED:
        obs.append(pooled_obs)
        exp.append(pooled_exp)
    elif low.any() and exp:
        # Too little to stand alone: fold it into the smallest regular bin.
        i = int(np.argmin(exp))
        obs[i] += pooled_obs
        exp[i] += pooled_exp
    return np.asarray(obs, float), np.asarray(exp, float), int(low.sum())


def goodness_of_fit(observed: np.ndarray, expected: np.ndarray) -> Chi2Result:
    """Pearson's test of observed counts against expected counts (same shape, any dimension).

    The expected counts are not rescaled to the observed total: a pdf that does
    not integrate to one fails here as it should.
    """
    obs, exp, pooled = _pool(np.ravel(observed).astype(float), np.ravel(expected).astype(float))
    if len(exp) < 2:
        return Chi2Result(0.0, 0, 1.0, pooled)
    statistic = float(np.sum((obs - exp) ** 2 / exp))
    dof = len(exp) - 1
    return Chi2Result(statistic, dof, float(sps.chi2.sf(statistic, dof)), pooled)


def homogeneity(counts_a: np.ndarray, counts_b: np.ndarray) -> Chi2Result:
    """Test whether two histograms come from the same distribution (2 x k contingency table).

    Cells whose expected count under the pooled distribution falls below
    MIN_EXPECTED in either row are merged first.
    """
    a = np.ravel(counts_a).astype(float)
    b = np.ravel(counts_b).astype(float)
    share_a = a.sum() / (a.sum() + b.sum())
    low = np.minimum(share_a, 1.0 - share_a) * (a + b) < MIN_EXPECTED
    table = np.stack([a[~low], b[~low]])
    if low.any():
        table = np.concatenate([table, [[a[low].sum()], [b[low].sum()]]], axis=1)
    table = table[:, table.sum(axis=0) > 0]
    if table.shape[1] < 2:
        return Chi2Result(0.0, 0, 1.0, int(low.sum()))
    res = sps.chi2_contingency(table, correction=False)
    return Chi2Result(float(res.statistic), int(res.dof), float(res.pvalue), int(low.sum()))
