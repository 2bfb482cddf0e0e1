"""The ufunc forms of the distribution functions return scipy.stats' bits, edges included: a family level or a
power figure does not move by their use."""
import numpy as np
import pytest
from scipy import stats as sps

from harness.statistics import distributions as d

RNG = np.random.default_rng(0)
EDGES_X = [0.0, -0.0, np.inf, -np.inf, np.nan, 1e300, -1e300, 40.0, -40.0, 1e-300]
X = np.concatenate([RNG.normal(0, 3, 4000), EDGES_X])
DOF = np.concatenate([RNG.uniform(0.5, 300, 4000), [1, 2, np.inf, 1e10, 7, 7, 7, 7, 7, 3]])
Q = np.concatenate([RNG.uniform(0, 1, 4000), [0, 1, 1e-300, 0.5, np.nan, 1 - 1e-16, 1e-12, 0.3, 0.3, 0.9]])
NC = RNG.normal(0, 5, X.size)
DOF2 = np.concatenate([RNG.uniform(0.5, 300, 4000), [3, np.inf, 2, 1, 7, 1e10, 7, 7, 0.5, 9]])


def same_bits(a, b) -> bool:
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    return a.shape == b.shape and bool(np.all((a == b) | (np.isnan(a) & np.isnan(b))))


@pytest.mark.parametrize("mine, theirs, args", [
    (d.t_sf, sps.t.sf, (X, DOF)),
    (d.t_isf, sps.t.isf, (Q, DOF)),
    (d.norm_sf, sps.norm.sf, (X,)),
    (d.norm_cdf, sps.norm.cdf, (X,)),
    (d.norm_isf, sps.norm.isf, (Q,)),
    (d.norm_pdf, sps.norm.pdf, (X,)),
    (d.nct_sf, sps.nct.sf, (X, DOF, NC)),
    (d.nct_cdf, sps.nct.cdf, (X, DOF, NC)),
    (d.chi2_sf, sps.chi2.sf, (X, DOF)),
    (d.f_ppf, sps.f.ppf, (Q, DOF, DOF2)),
])
def test_same_bits_as_scipy_stats(mine, theirs, args):
    with np.errstate(all="ignore"):
        assert same_bits(mine(*args), theirs(*args))
        assert same_bits(mine(*(a[:1] for a in args)), theirs(*(a[:1] for a in args)))
        assert same_bits(mine(*(float(a[7]) for a in args)), theirs(*(float(a[7]) for a in args)))


@pytest.mark.parametrize("dof", [0.0, -1.0, np.nan])
def test_no_distribution_is_nan(dof):
    assert np.isnan(d.t_sf(1.0, dof)) and np.isnan(d.t_isf(0.1, dof)) and np.isnan(d.nct_sf(1.0, dof, 2.0))
    assert np.isnan(d.chi2_sf(1.0, dof)) and np.isnan(d.f_ppf(0.5, dof, 3.0)) and np.isnan(d.f_ppf(0.5, 3.0, dof))


def test_the_comparison_catches_a_changed_bit():
    """The check above can fail: one ulp off is not the same bits."""
    assert not same_bits(np.nextafter(d.t_sf(X[:5], DOF[:5]), 1.0), sps.t.sf(X[:5], DOF[:5]))
