"""The few distribution functions the tests evaluate in their inner loops, as scipy.special's ufuncs.

scipy.stats' `t.sf(x, dof)` checks and broadcasts its arguments on every call, which costs more than the
special function itself on the small arrays a family level or a power search evaluates tens of thousands
of times. These call the ufuncs scipy.stats calls, so they return the same bits wherever the arguments are
valid (dof > 0 or NaN, any x: tests/statistics/test_distributions.py), and NaN where scipy.stats would."""
from __future__ import annotations

import numpy as np
from scipy import special as sc

_SQRT_2PI = np.sqrt(2.0 * np.pi)


def _valid_dof(dof, out):
    # scipy.stats' argument check: dof <= 0 (or NaN) is no distribution (NaN); ufuncs would answer something.
    valid = np.asarray(dof) > 0
    return out if valid.all() else np.where(valid, out, np.nan)


def t_sf(x, dof):
    """Student's t survival function, as scipy.stats.t.sf."""
    return _valid_dof(dof, sc.stdtr(dof, -np.asarray(x, np.float64)))


def t_isf(q, dof):
    """Student's t inverse survival function, as scipy.stats.t.isf."""
    q = np.asarray(q, np.float64)
    return _valid_dof(dof, np.where(q == 0, np.inf, np.where(q == 1, -np.inf, -sc.stdtrit(dof, q))))


def chi2_sf(x, dof):
    """Chi-square survival function, as scipy.stats.chi2.sf (1 below the support, 0 at infinity)."""
    x = np.asarray(x, np.float64)
    with np.errstate(invalid="ignore"):
        sf = np.where(x < 0, 1.0, np.where(x == np.inf, 0.0, sc.chdtrc(dof, x)))
    return _valid_dof(dof, sf)


def f_ppf(q, dfn, dfd):
    """F distribution's quantile function, as scipy.stats.f.ppf."""
    q = np.asarray(q, np.float64)
    with np.errstate(invalid="ignore"):
        ppf = np.where(q == 0, 0.0, np.where(q == 1, np.inf, sc.fdtri(dfn, dfd, q)))
    return _valid_dof(dfn, _valid_dof(dfd, ppf))


def norm_sf(x):
    return sc.ndtr(-np.asarray(x, np.float64))


def norm_cdf(x):
    return sc.ndtr(x)


def norm_isf(q):
    return -sc.ndtri(q)


def norm_ppf(p):
    return sc.ndtri(p)


def norm_pdf(x):
    with np.errstate(over="ignore"):
        return np.exp(-np.asarray(x, np.float64) ** 2 / 2.0) / _SQRT_2PI


def nct_sf(x, dof, nc):
    """Noncentral t survival function, as scipy.stats.nct.sf."""
    x = np.asarray(x, np.float64)
    with np.errstate(over="ignore"):
        sf = np.clip(sc._ufuncs._nct_sf(x, dof, nc), 0, 1)
    return _valid_dof(dof, np.where(x == np.inf, 0.0, np.where(x == -np.inf, 1.0, sf)))


def nct_cdf(x, dof, nc):
    """Noncentral t distribution function, as scipy.stats.nct.cdf."""
    return _valid_dof(dof, sc.nctdtr(dof, nc, x))
