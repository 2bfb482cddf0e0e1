"""The detectable bias (harness.statistics.detectable_bias) against its definition: brentq on the noncentral t's
two-sided power, channel by channel; and its root search against known roots."""
import numpy as np
import pytest
from scipy import stats as sps
from scipy.optimize import brentq

from harness.statistics.detectable_bias import half_power_bias, increasing_root
from harness.statistics.welch import BatchStats


def two_sided_power(crit, dof, nc):
    """P(|T| > crit) for T noncentral t(dof, nc): the lower tail P(T < -crit) is P(-T > crit), -T ~ t(dof, -nc)."""
    return sps.nct.sf(crit, dof, nc) + sps.nct.sf(crit, dof, -nc)


def half_power_by_brentq(mean, se, dof, level, union_share=1.0):
    """b with 1 - prod_c (1 - P(|t'_c| > crit))^share = 0.5, t'_c noncentral t(dof, b |mean_c| / se_c); a
    channel without a finite mean or a standard error has no noncentrality (it rejects at the level)."""
    mean, se, dof = (a.ravel() for a in np.broadcast_arrays(*map(np.atleast_1d, (mean, se, dof))))
    ratio = np.array([abs(m) / s if np.isfinite(m) and s > 0 else 0.0 for m, s in zip(mean, se)])
    crit = sps.t.isf(level / 2, dof)

    def found(bias):
        return 1 - np.prod((1 - two_sided_power(crit, dof, bias * ratio)) ** union_share) - 0.5

    return brentq(found, 1e-9, 1e5, xtol=1e-14, rtol=1e-10)


@pytest.mark.parametrize("level, dof", [(0.2, 30.0), (1e-3, 7.0), (1e-6, 2.0)])
def test_half_power_bias_of_one_channel(level, dof):
    mean, se = np.array([[2.0]]), np.array([[0.1]])
    got = half_power_bias(BatchStats(mean, se**2, 8), se, np.array([[dof]]), level, 0.0)
    assert got.shape == (1,)
    assert got[0] == pytest.approx(half_power_by_brentq(mean, se, dof, level), rel=1e-6)


def test_half_power_bias_of_a_small_relative_mean_is_large():
    mean, se = np.array([0.01, 0.0, 0.0]), np.array([1.0, 1.0, 1.0])
    got = half_power_bias(BatchStats(mean, se**2, 8), se, np.full(3, 20.0), 1e-3, 0.0)
    assert got[0] > 100
    assert got[0] == pytest.approx(half_power_by_brentq(mean, se, 20.0, 1e-3), rel=1e-6)


def test_half_power_bias_of_independent_channels_and_of_elements_without_a_mean():
    rng = np.random.default_rng(32)
    mean = rng.uniform(0.2, 1.0, (2, 4, 3))
    se = rng.uniform(0.02, 0.05, (2, 4, 3))
    dof = rng.uniform(5, 20, (2, 4, 3))
    mean[1, 2] = 0.0  # no channel with a mean: no bias can be found
    mean[0, 1, 0], se[0, 1, 1] = np.nan, 0.0  # channels that cannot tell
    got = half_power_bias(BatchStats(mean, se**2, 8), se, dof, 1e-3, 0.0)
    assert got.shape == (2, 4)
    for i in range(2):
        for j in range(4):
            if i == 1 and j == 2:
                assert got[i, j] == np.inf
            else:
                expected = half_power_by_brentq(mean[i, j], se[i, j], dof[i, j], 1e-3)
                assert got[i, j] == pytest.approx(expected, rel=1e-6)


def test_half_power_bias_of_correlated_channels_counts_them_as_the_null_does():
    from harness.statistics.family_level import channel_union
    mean, se = np.array([1.0, 0.8, 0.9]), np.array([0.05, 0.05, 0.05])
    share = channel_union(1e-3, 3, 0.5) / 3
    got = half_power_bias(BatchStats(mean, se**2, 8), se, np.full(3, 12.0), 1e-3, 0.5)
    assert got[0] == pytest.approx(half_power_by_brentq(mean, se, 12.0, 1e-3, share), rel=1e-6)


def test_increasing_root_finds_each_elements_crossing_evaluating_each_until_it_is_found():
    a = np.array([1e-6, 0.5, 3.0, 7.9, -1.0, 9.0])  # the last two cross nowhere in [0, 2]
    evaluated = []

    def f(x, index):
        evaluated.append(index.size)
        return x**3 - a[index]

    got = increasing_root(f, np.zeros(a.shape), np.full(a.shape, 2.0))
    assert got[:4] == pytest.approx(np.cbrt(a[:4]), rel=1e-9)
    assert evaluated[:2] == [6, 6] and max(evaluated[2:]) <= 4  # the ends once, then only those searched
    assert sum(evaluated[2:]) < 4 * 34  # a bisection to the same precision: 34 steps each
