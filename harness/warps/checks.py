"""The individual checks of a warp against its pdf. Each returns a CheckResult.

Statistical checks carry a p-value and are decided later, once the number of
tests in the run (and so the Sidak-corrected level) is known.
"""
from __future__ import annotations

import threading
from typing import Any, Callable

import numpy as np

from harness.statistics.chi2 import goodness_of_fit, homogeneity
from harness.statistics.cubature import CellIntegrals, integrate_cells
from harness.statistics.factors import name_factor
from harness.warps.domains import Domain
from harness.statistics.constants import HISTOGRAM_RES, NORMALISATION_TOLERANCE
from harness.warps.bins import Bins, bin_indices, equal_probability_bins, pilot_bins, uniform_bins
from harness.warps.check_result import CheckResult, not_judged
from harness.warps.findings import classify, count, describe, merge, off_domain, summarize

Sampler = Callable[[np.ndarray], np.ndarray]
Pdf = Callable[[np.ndarray], np.ndarray]


def factor_phrase(ratio: float, tolerance: float) -> str | None:
    """"pi^2 too large" for a ratio of pi^2 (within `tolerance`, see statistics.factors), "pi^2 too small" for
    1/pi^2; None when the ratio is no named factor."""
    if not (np.isfinite(ratio) and ratio > 0):
        return None
    name = name_factor(ratio if ratio >= 1 else 1 / ratio, tolerance)
    return None if name is None else f"{name} too {'large' if ratio >= 1 else 'small'}"


def as_points(x: Any, n: int, name: str) -> np.ndarray:
    a = np.asarray(x, dtype=np.float64)
    if a.ndim != 2 or a.shape[0] != n:
        raise ValueError(f"{name} returned shape {a.shape}, expected ({n}, 2) or ({n}, 3)")
    return a


def as_values(x: Any, n: int, name: str) -> np.ndarray:
    a = np.asarray(x, dtype=np.float64).reshape(-1)
    if a.shape[0] != n:
        raise ValueError(f"{name} returned {a.shape[0]} values for {n} points")
    return a


def parameter_density(domain: Domain, pdf: Pdf) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """pdf as a density over the domain's parameter square: pdf(from_param(s, t)) * measure."""
    def density(s: np.ndarray, t: np.ndarray) -> np.ndarray:
        return as_values(pdf(domain.from_param(s, t)), len(s), "pdf") * domain.measure
    return density


#: Domains whose t is an azimuth: undefined at x = y = 0 (the poles, the disk's centre).
_AZIMUTHAL = ("disk", "sphere", "hemisphere")


def histogram(domain: Domain, points: np.ndarray, bins: Bins | int = HISTOGRAM_RES,
              param: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Counts of points (assumed inside the domain) per cell: `bins`' cells, or a res x res uniform grid.

    A point where the azimuth is undefined (x = y = 0 on the disk, sphere, hemisphere: a float32 sampler
    rounds directions within about 2e-4 rad of the pole onto it) counts 1/cols in every cell of its row,
    as the directions it stands for are spread over all azimuths; binning it at t = 0 would pile them up.
    `param`: domain.to_param(points), when the caller has it already (one set of points in two sets of cells).
    """
    bins = uniform_bins(bins) if isinstance(bins, (int, np.integer)) else bins
    s, t = domain.to_param(points) if param is None else param
    i, j = bin_indices(bins.s_edges, np.asarray(s)), bin_indices(bins.t_edges, np.asarray(t))
    rows, cols = bins.shape
    pole = (points[:, 0] == 0) & (points[:, 1] == 0) if domain.name in _AZIMUTHAL else np.zeros(len(i), bool)
    counts = np.bincount(i[~pole] * cols + j[~pole], minlength=rows * cols).reshape(rows, cols).astype(float)
    counts += (np.bincount(i[pole], minlength=rows) / cols)[:, None]
    return counts


def parameter_grid(domain: Domain, s_edges: np.ndarray | None = None, t_edges: np.ndarray | None = None) -> np.ndarray:
    """Points of the domain at the centres of cells of its parameter square: a uniform HISTOGRAM_RES grid, or the
    cells with these edges (equal-probability cells put their centres where the mass is)."""
    uniform = np.arange(HISTOGRAM_RES + 1) / HISTOGRAM_RES
    s_edges, t_edges = (uniform if e is None else np.asarray(e) for e in (s_edges, t_edges))
    s, t = ((e[:-1] + e[1:]) / 2 for e in (s_edges, t_edges))
    return domain.from_param(*[a.ravel() for a in np.meshgrid(s, t, indexing="ij")])


#: The fewest pilot points whose quantiles give cells (fewer: the pdf's own quantiles).
MIN_PILOT = 10_000
#: Expected samples a cell at least, where fewer samples than HISTOGRAM_RES^2 times this are drawn: fewer cells,
#: so that a small run's cells are not all pooled (below 5 expected) and the test judges something.
SAMPLES_PER_CELL = 16


def cells_per_axis(samples: int) -> int:
    """HISTOGRAM_RES cells per axis, fewer where `samples` would leave a cell fewer than SAMPLES_PER_CELL."""
    return int(min(HISTOGRAM_RES, max(2, np.sqrt(samples / SAMPLES_PER_CELL))))
#: Points of the parameter square at which a pdf's values identify it, and how many pdfs' cells are kept.
_FINGERPRINT = np.random.default_rng(20240).random((2, 4096))
_KEPT = 32
_recent_cells: dict[tuple, Bins] = {}
_recent_lock = threading.Lock()  # rows checked side by side share the cache


def equal_probability_cells(domain: Domain, pdf: Pdf, samples: int, quantum: float,
                            pilot: np.ndarray | None = None) -> tuple[Bins, CellIntegrals]:
    """The chi-square cells of `pdf` for `samples` samples, as fine as their rounding `quantum` allows (see
    warp_bins.sample_quantum), and the pdf's integral over each.

    The cells of the last few pdfs are kept, by the pdf's values at 4096 fixed points: the same pdf at another
    seed (tests, a user's loop) gets its cells again without the quantile search. Any cells fixed before the
    samples are drawn give a valid test, and the integrals are always this pdf's. `pilot`: points drawn apart
    from the tested ones, whose marginal quantiles give the cells instead of the pdf's (warps.bins.pilot_bins;
    not kept).
    """
    res = cells_per_axis(samples)
    if pilot is not None and len(pilot) >= MIN_PILOT:
        s, t = domain.to_param(pilot)
        bins = pilot_bins(parameter_density(domain, pdf), s, t, res, samples, quantum, domain.s_breaks)
        return bins, expected_probabilities(domain, pdf, bins)
    values = np.asarray(pdf(domain.from_param(*_FINGERPRINT)), dtype=np.float64)
    key = (domain.name, samples, quantum, values.tobytes())
    with _recent_lock:
        bins = _recent_cells.get(key)
    if bins is None:
        bins = equal_probability_bins(parameter_density(domain, pdf), res, samples, quantum)
        with _recent_lock:
            _recent_cells[key] = bins
            while len(_recent_cells) > _KEPT:
                del _recent_cells[next(iter(_recent_cells))]
    return bins, expected_probabilities(domain, pdf, bins)


def expected_probabilities(domain: Domain, pdf: Pdf, bins: Bins | int = HISTOGRAM_RES) -> CellIntegrals:
    """Probability of each cell under pdf (`bins`' cells, or a res x res uniform grid), integrated adaptively."""
    bins = uniform_bins(bins) if isinstance(bins, (int, np.integer)) else bins
    return integrate_cells(parameter_density(domain, pdf), bins.s_edges, bins.t_edges)


def lost_samples(outside: int, nonfinite: int) -> str:
    """How many samples never reached a histogram: "12 NaN/Inf samples", "3 samples outside the domain"."""
    parts = [f"{nonfinite} NaN/Inf samples"] if nonfinite else []
    if outside > nonfinite:
        parts.append(f"{outside - nonfinite} samples outside the domain")
    return " and ".join(parts)


def chi2_check(observed: np.ndarray, probabilities: np.ndarray, outside: int, bins: Bins | None = None,
               nonfinite: int = 0, against: str = "") -> CheckResult:
    """Goodness of fit of the histogram of samples against cell probabilities (of the pdf, or of a target).

    Expected counts are N * (cell integral of the density), N counting the samples outside the domain too
    (`outside`, of which `nonfinite` are NaN/Inf: a hard failure); `bins` (the cells, if given) are described in
    the details; `against` ends the summary (e.g. "against the tent (1-|x|)(1-|y|)").
    """
    n = observed.sum() + outside
    expected = probabilities * n
    hard = None
    if not np.all(np.isfinite(probabilities)):
        hard = "pdf is not finite somewhere in the domain"
    elif np.any(probabilities < 0):
        hard = "pdf is negative somewhere in the domain"
    elif outside:
        hard = lost_samples(outside, nonfinite)
    else:
        stray = int(observed[expected <= 0].sum())
        if stray:
            hard = f"{stray} samples in cells where the pdf is zero"
    tail = f" {against}" if against else ""
    if hard:
        return CheckResult(False, 0.0, hard + (f" ({against})" if against else ""), p_value=0.0, hard_failure=hard)
    res = goodness_of_fit(observed, expected)
    details = {"statistic": res.statistic, "dof": res.dof, "pooled_cells": res.pooled_cells, "samples": int(n),
               **(bins.to_json() if bins is not None else {})}
    if res.not_judged:
        return not_judged(res.not_judged + tail, **details)
    return CheckResult(None, res.p_value, f"p = {res.p_value:.3g}{tail}", p_value=res.p_value, details=details)


def normalisation_check(integral: float, error: float) -> CheckResult:
    """The pdf's integral over the domain is 1 within NORMALISATION_TOLERANCE. A failure names the factor when
    the integral is one (pi^2, 1/(4pi), 2, ...: statistics.factors), e.g. "pdf integrates to 9.8696 = pi^2: the
    pdf is pi^2 too large"."""
    ok = bool(np.isfinite(integral) and abs(integral - 1.0) <= NORMALISATION_TOLERANCE)
    details = {"tolerance": NORMALISATION_TOLERANCE, "integration_error": error}
    if ok:
        return CheckResult(ok, float(integral), f"integral = {integral:.6f}", details=details)
    summary = f"pdf integrates to {integral:.5g}"
    phrase = factor_phrase(integral, NORMALISATION_TOLERANCE)
    if phrase:
        details["factor"] = name_factor(integral, NORMALISATION_TOLERANCE)
        summary += f" = {details['factor']}: the pdf is {phrase}"
    return CheckResult(ok, float(integral), summary, details=details)


def domain_check(domain: Domain, points: np.ndarray, pdf: Pdf, rng: np.random.Generator,
                 u: np.ndarray | None = None, input_dtype: Any = np.float64) -> CheckResult:
    """Samples lie in the domain, the pdf is finite and > 0 at them, and 0 outside the domain.

    A pdf of 0 at a sample on the domain's boundary is a warning, not a failure, and so is any failure
    of a sample whose input u (N, 2), as the sampler received it (`input_dtype`), has a coordinate of 1.
    The figure counts failures; `findings` lists them (then the warnings) with their inputs.
    """
    values = as_values(pdf(points), len(points), "pdf")
    at_one = None if u is None else np.any(u.astype(input_dtype) == 1.0, axis=1)
    codes, underlying = classify(domain, points, values, at_one)
    groups = [describe(codes, underlying, points, values, u=u)]
    leak = 0
    if domain.outside is not None:
        probes = domain.outside(rng, 10_000)
        probe_values = as_values(pdf(probes), len(probes), "pdf")
        leak = int(np.count_nonzero(probe_values != 0))
        groups.append(off_domain(probes, probe_values))
    findings = merge(groups)
    violations = sum(f.count for f in findings if f.severity == "FAIL")
    return CheckResult(violations == 0, float(violations), summarize(findings, "ok"), findings=findings,
                       details={"samples_outside": int(np.count_nonzero(~domain.contains(points))),
                                "bad_pdf_at_samples": sum(count(codes, k) for k in
                                                          ("nan_pdf", "negative_pdf", "zero_pdf_inside")),
                                "pdf_nonzero_outside": leak,
                                "zero_pdf_on_boundary": count(codes, "zero_pdf_boundary"),
                                "failures_at_u_one": count(codes, "at_u_one")})


def homogeneity_check(observed: np.ndarray, reference_observed: np.ndarray, outside: int = 0,
                      nonfinite: int = 0) -> CheckResult:
    """Our samples and the reference sampler's samples come from one distribution.

    Our samples that never reached `observed` (`outside` the domain, `nonfinite` of them NaN/Inf) are a hard
    failure, as in chi2_check; an empty histogram is not judged (a failure), never a p-value.
    """
    res = homogeneity(observed, reference_observed)
    details = {"statistic": res.statistic, "dof": res.dof, "pooled_cells": res.pooled_cells}
    if outside:
        hard = lost_samples(outside, nonfinite)
        if res.not_judged:
            hard += f"; not judged: {res.not_judged}"
        return CheckResult(False, 0.0, hard, details=details, p_value=0.0, hard_failure=hard,
                           not_judged=res.not_judged)
    if res.not_judged:
        return not_judged(res.not_judged, **details)
    return CheckResult(None, res.p_value, f"p = {res.p_value:.3g}", p_value=res.p_value, details=details)
