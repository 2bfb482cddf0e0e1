"""The individual checks of a warp against its pdf. Each returns a CheckResult.

Statistical checks carry a p-value and are decided later, once the number of
tests in the run (and so the Sidak-corrected level) is known.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from harness.statistics.chi2 import goodness_of_fit, homogeneity
from harness.statistics.cubature import CellIntegrals, integrate_cells
from harness.warps.domains import Domain
from harness.statistics.constants import HISTOGRAM_RES, NORMALISATION_TOLERANCE, PDF_RELATIVE_TOLERANCE
from harness.warps.bins import Bins, bin_indices, uniform_bins
from harness.warps.findings import Finding, classify, count, describe, merge, off_domain, summarize

Sampler = Callable[[np.ndarray], np.ndarray]
Pdf = Callable[[np.ndarray], np.ndarray]


@dataclass
class CheckResult:
    """One check's verdict, its headline figure and the numbers behind it.

    passed is None for a check that was skipped, and for a statistical check
    whose p-value has not been compared with the run's level yet. A check that
    passed with WARN findings (see warp_findings) has the verdict WARN.
    """

    passed: bool | None
    figure: float | None
    summary: str
    details: dict[str, Any] = field(default_factory=dict)
    p_value: float | None = None
    #: A failure that no significance level can excuse (samples outside the domain, NaN, ...).
    hard_failure: str | None = None
    skipped: bool = False
    #: What the check found at individual samples, most serious first (failures, then warnings).
    findings: list[Finding] = field(default_factory=list)

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "WARN"]

    @property
    def verdict(self) -> str | None:
        """"PASS", "WARN" (passed, with warnings), "FAIL", "SKIP", or None while undecided."""
        if self.skipped:
            return "SKIP"
        if self.passed is None:
            return None
        return "FAIL" if not self.passed else "WARN" if self.warnings else "PASS"

    def decide(self, level: float) -> None:
        """Set `passed` for a statistical check from its p-value and the per-test level."""
        if self.p_value is not None:
            self.passed = self.hard_failure is None and self.p_value >= level
            self.details["level"] = level

    def to_json(self) -> dict[str, Any]:
        out = {"pass": self.passed, "verdict": self.verdict, "figure": self.figure, "summary": self.summary}
        if self.p_value is not None:
            out["p_value"] = self.p_value
        if self.hard_failure:
            out["hard_failure"] = self.hard_failure
        if self.skipped:
            out["skipped"] = True
        if self.findings:
            out["findings"] = [f.to_json() for f in self.findings]
        out.update(self.details)
        return out


def skipped(reason: str) -> CheckResult:
    return CheckResult(None, None, f"skipped: {reason}", skipped=True)


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


def histogram(domain: Domain, points: np.ndarray, bins: Bins | int = HISTOGRAM_RES) -> np.ndarray:
    """Counts of points (assumed inside the domain) per cell: `bins`' cells, or a res x res uniform grid.

    A point where the azimuth is undefined (x = y = 0 on the disk, sphere, hemisphere: a float32 sampler
    rounds directions within about 2e-4 rad of the pole onto it) counts 1/cols in every cell of its row,
    as the directions it stands for are spread over all azimuths; binning it at t = 0 would pile them up.
    """
    bins = uniform_bins(bins) if isinstance(bins, (int, np.integer)) else bins
    s, t = domain.to_param(points)
    i, j = bin_indices(bins.s_edges, np.asarray(s)), bin_indices(bins.t_edges, np.asarray(t))
    rows, cols = bins.shape
    pole = (points[:, 0] == 0) & (points[:, 1] == 0) if domain.name in _AZIMUTHAL else np.zeros(len(i), bool)
    counts = np.bincount(i[~pole] * cols + j[~pole], minlength=rows * cols).reshape(rows, cols).astype(float)
    counts += (np.bincount(i[pole], minlength=rows) / cols)[:, None]
    return counts


def expected_probabilities(domain: Domain, pdf: Pdf, bins: Bins | int = HISTOGRAM_RES) -> CellIntegrals:
    """Probability of each cell under pdf (`bins`' cells, or a res x res uniform grid), integrated adaptively."""
    bins = uniform_bins(bins) if isinstance(bins, (int, np.integer)) else bins
    return integrate_cells(parameter_density(domain, pdf), bins.s_edges, bins.t_edges)


def chi2_check(observed: np.ndarray, probabilities: np.ndarray, outside: int, bins: Bins | None = None) -> CheckResult:
    """Goodness of fit of the histogram of samples against the pdf's cell probabilities.

    Expected counts are N * (cell integral of the pdf), N counting the samples outside the domain too;
    `bins` (the cells, if given) are described in the details.
    """
    n = observed.sum() + outside
    expected = probabilities * n
    hard = None
    if not np.all(np.isfinite(probabilities)):
        hard = "pdf is not finite somewhere in the domain"
    elif np.any(probabilities < 0):
        hard = "pdf is negative somewhere in the domain"
    elif outside:
        hard = f"{outside} samples outside the domain"
    else:
        stray = int(observed[expected <= 0].sum())
        if stray:
            hard = f"{stray} samples in cells where the pdf is zero"
    if hard:
        return CheckResult(False, 0.0, hard, p_value=0.0, hard_failure=hard)
    res = goodness_of_fit(observed, expected)
    return CheckResult(None, res.p_value, f"p = {res.p_value:.3g}", p_value=res.p_value,
                       details={"statistic": res.statistic, "dof": res.dof,
                                "pooled_cells": res.pooled_cells, "samples": int(n),
                                **(bins.to_json() if bins is not None else {})})


def normalisation_check(integral: float, error: float) -> CheckResult:
    """The pdf's integral over the domain is 1 within NORMALISATION_TOLERANCE."""
    ok = bool(np.isfinite(integral) and abs(integral - 1.0) <= NORMALISATION_TOLERANCE)
    return CheckResult(ok, float(integral), f"integral = {integral:.6f}",
                       details={"tolerance": NORMALISATION_TOLERANCE, "integration_error": error})


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


def _rounding_sensitivity(points: np.ndarray, pdf: Pdf) -> np.ndarray:
    """How much pdf changes when any coordinate of a point moves by one float32 ulp.

    A float32 formula that cancels (1 - cos^2 near the pole) is this sensitive
    to its input's rounding, so no implementation can be asked to agree with it
    more closely than that.
    """
    base = as_values(pdf(points), len(points), "pdf")
    worst = np.zeros(len(points))
    p32 = points.astype(np.float32)
    for axis in range(points.shape[1]):
        for direction in (-np.inf, np.inf):
            moved = p32.copy()
            moved[:, axis] = np.nextafter(p32[:, axis], np.float32(direction))
            diff = np.abs(as_values(pdf(moved.astype(np.float64)), len(points), "pdf") - base)
            worst = np.maximum(worst, np.nan_to_num(diff))
    return worst


def pdf_agreement_check(points: np.ndarray, pdf: Pdf, reference_pdf: Pdf) -> CheckResult:
    """Our pdf equals the reference pdf at the same points inside the support.

    Allowed difference per point: PDF_RELATIVE_TOLERANCE of the reference value,
    plus twice the reference's own change under one-ulp moves of the point.
    """
    ref = as_values(reference_pdf(points), len(points), "reference pdf")
    inside = ref > 0
    points, ref = points[inside], ref[inside]
    ours = as_values(pdf(points), len(points), "pdf")
    slack = 2.0 * _rounding_sensitivity(points, reference_pdf)
    excess = np.abs(ours - ref) - slack
    rel = np.where(np.isfinite(ours), np.maximum(excess, 0.0) / ref, np.inf)
    worst = float(np.max(rel, initial=0.0))
    raw = float(np.max(np.abs(ours - ref) / ref, initial=0.0))
    ok = worst <= PDF_RELATIVE_TOLERANCE
    needed_slack = int(np.count_nonzero((np.abs(ours - ref) > PDF_RELATIVE_TOLERANCE * ref)
                                        & (rel <= PDF_RELATIVE_TOLERANCE)))
    summary = f"max rel. diff {raw:.2g}"
    if needed_slack:
        summary += f" ({needed_slack} pts within ref. rounding)"
    detail = {"points": len(points), "tolerance": PDF_RELATIVE_TOLERANCE, "max_relative_difference": raw,
              "points_within_reference_rounding": needed_slack}
    if not ok:
        k = int(np.argmax(rel))
        detail["worst_point"] = points[k].tolist()
        detail["worst_values"] = [float(ours[k]), float(ref[k])]
    return CheckResult(ok, worst, summary, details=detail)


def homogeneity_check(observed: np.ndarray, reference_observed: np.ndarray) -> CheckResult:
    """Our samples and the reference sampler's samples come from one distribution."""
    res = homogeneity(observed, reference_observed)
    return CheckResult(None, res.p_value, f"p = {res.p_value:.3g}", p_value=res.p_value,
                       details={"statistic": res.statistic, "dof": res.dof, "pooled_cells": res.pooled_cells})


def hard_input_grid() -> np.ndarray:
    """u on a grid of values that break careless warps, in both coordinates.

    0, the smallest positive double and float, the smallest normal float, 0.5,
    one ulp below 1 in double and in float, and 1.
    """
    values = np.array([0.0, 5e-324, float(np.float32(1.4e-45)), float(np.finfo(np.float32).tiny),
                       0.5, 1.0 - 2.0 ** -53, 1.0 - 2.0 ** -24, 1.0])
    a, b = np.meshgrid(values, values, indexing="ij")
    return np.stack([a.ravel(), b.ravel()], axis=-1)


def hard_inputs_check(domain: Domain, variants: dict[str, tuple[Sampler, Pdf]]) -> CheckResult:
    """On hard inputs every sample is finite and in the domain, and its pdf finite and positive.

    `variants` maps a label (e.g. "alpha=1e-4") to a (sample, pdf) pair. Warnings, not failures: a pdf
    of 0 at a sample on the domain's boundary, and anything at an input with a coordinate u = 1 (outside
    [0, 1)). A sampler with an `input_dtype` attribute (float32 for Dr.Jit functions, see warp_adapters)
    is judged on u as it received it. `findings` come most serious first: NaN samples, naming their u.
    The figure is the number of NaN/Inf samples at inputs in [0, 1).
    """
    u = hard_input_grid()
    groups = []
    for label, (sample, pdf) in variants.items():
        points = as_points(sample(u), len(u), "sample")
        values = as_values(pdf(points), len(points), "pdf")
        seen = u.astype(getattr(sample, "input_dtype", np.float64))
        codes, underlying = classify(domain, points, values, np.any(seen == 1.0, axis=1))
        groups.append(describe(codes, underlying, points, values, u=u, seen=seen, label=label))
    findings = merge(groups)
    n = {f.kind.key: f.count for f in findings}
    nonfinite = n.get("nan_sample", 0)
    ok = not any(f.severity == "FAIL" for f in findings)
    details = {"nan_inf": nonfinite, "outside": n.get("outside", 0),
               "bad_pdf": sum(n.get(k, 0) for k in ("nan_pdf", "negative_pdf", "zero_pdf_inside")),
               "zero_pdf_on_boundary": n.get("zero_pdf_boundary", 0), "failures_at_u_one": n.get("at_u_one", 0),
               "inputs": len(u) * len(variants), "variants": list(variants)}
    return CheckResult(ok, float(nonfinite), summarize(findings, f"NaN/Inf {nonfinite}"), details=details,
                       findings=findings)
