"""Warp conformance: a sampler checked against its own pdf, and against a reference implementation.

Public API::

    result = check_warp(sample, pdf, "disk", seed=0)
    result.passed, result.checks["chi2"].figure

`sample` maps an (N, 2) array of uniforms in [0,1)^2 to (N, 2) or (N, 3)
points, `pdf` maps such points to (N,) densities (w.r.t. area on 2D domains,
solid angle on the sphere and hemisphere). Checks that need a reference
implementation are skipped unless one is given. check_warp also takes float32
results, constant pdfs and Mitsuba/Dr.Jit functions (see warp_adapters).

Each check is PASS, WARN (passed, with warnings such as a pdf of 0 on the
domain's boundary, see warp_findings) or FAIL; a warp passes when no check fails.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from harness.warps import checks as wc
from harness.statistics.cubature import CellIntegrals
from harness.warps.domains import Domain, get_domain
from harness.engines.base import WarpFunctions
from harness.statistics.constants import HISTOGRAM_RES, SIGNIFICANCE, WARP_SAMPLES, sidak_level
from harness.warps.adapters import NumpyPdf, NumpySampler
from harness.warps.bins import Bins, equal_probability_bins, sample_quantum
from harness.warps.throughput import throughput_check

#: The checks, in the order reports show them.
CHECK_NAMES = ("chi2", "normalisation", "domain", "pdf_vs_mitsuba", "samples_vs_mitsuba",
               "hard_inputs", "throughput")


@dataclass
class WarpResult:
    """Every check of one warp (with one parameter value), and the histograms behind them."""

    warp: str
    params: Any
    domain: str
    checks: dict[str, wc.CheckResult]
    #: Histograms over the parameter square: our samples, the pdf's expectation, the reference's samples.
    observed: np.ndarray
    expected: np.ndarray
    reference_observed: np.ndarray | None
    seconds: float
    seed: int
    #: The histograms' cells (equal-probability in the pdf's marginals; see warp_bins).
    bins: Bins | None = None

    @property
    def passed(self) -> bool:
        return all(bool(c.passed) for c in self.checks.values() if not c.skipped)

    @property
    def warnings(self) -> int:
        """How many checks passed with warnings."""
        return sum(c.verdict == "WARN" for c in self.checks.values())

    @property
    def verdict(self) -> str:
        """"FAIL" if a check fails, else "WARN" if one warns (the warp still passes), else "PASS"."""
        return "FAIL" if not self.passed else "WARN" if self.warnings else "PASS"

    @property
    def label(self) -> str:
        return self.warp if self.params is None else f"{self.warp} {format_params(self.params)}"

    def to_json(self) -> dict[str, Any]:
        return {"warp": self.warp, "params": self.params, "domain": self.domain, "pass": self.passed,
                "verdict": self.verdict, "warnings": self.warnings, "seed": self.seed, "seconds": self.seconds,
                "checks": {k: c.to_json() for k, c in self.checks.items()}}


def format_params(params: Any) -> str:
    if isinstance(params, dict):
        return ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in params.items())
    return str(params)


def evaluate_warp(sample: wc.Sampler, pdf: wc.Pdf, domain: str, *, name: str = "user warp",
                  params: Any = None, seed: int = 0, samples: int = WARP_SAMPLES,
                  reference: WarpFunctions | None = None, native_run=None,
                  hard_variants: dict[str, tuple[wc.Sampler, wc.Pdf]] | None = None,
                  judge_throughput: bool = True) -> WarpResult:
    """Run every check; statistical ones are left undecided (see `decide`). A sampler taking float32 (its
    `input_dtype`) gets float32 uniforms, all in [0, 1); `judge_throughput` False reports the throughput
    without a floor (a user's code)."""
    start = time.perf_counter()
    dom = get_domain(domain)
    rng = np.random.default_rng(seed)
    if getattr(sample, "input_dtype", np.float64) == np.float32:
        u = rng.random((samples, 2), dtype=np.float32).astype(np.float64)
    else:
        u = rng.random((samples, 2))
    points = wc.as_points(sample(u), samples, "sample")
    if points.shape[1] != dom.dim:
        raise ValueError(f"sample returned {points.shape[1]}D points; the {domain} domain is {dom.dim}D")
    inside = dom.inside(points)
    ref_points = None if reference is None else wc.as_points(
        reference.sample(np.random.default_rng([seed, 1]).random((samples, 2))), samples, "reference sample")
    bins, cells = equal_probability_cells(dom, pdf, samples, points[inside],
                                          *(() if ref_points is None else (ref_points,)))
    observed = wc.histogram(dom, points[inside], bins)

    checks = {
        "chi2": wc.chi2_check(observed, cells.values, int(np.count_nonzero(~inside)), bins),
        "normalisation": wc.normalisation_check(float(cells.values.sum()), cells.error),
        "domain": wc.domain_check(dom, points, pdf, rng, u, getattr(sample, "input_dtype", np.float64)),
    }
    reference_observed = None
    if reference is None:
        checks["pdf_vs_mitsuba"] = wc.skipped("no reference implementation")
        checks["samples_vs_mitsuba"] = wc.skipped("no reference implementation")
    else:
        probe = points[inside][:100_000]
        centres = (np.arange(HISTOGRAM_RES) + 0.5) / HISTOGRAM_RES  # a uniform grid over the parameter square
        grid = dom.from_param(*[a.ravel() for a in np.meshgrid(centres, centres, indexing="ij")])
        checks["pdf_vs_mitsuba"] = wc.pdf_agreement_check(np.concatenate([probe, grid]), pdf, reference.pdf)
        reference_observed = wc.histogram(dom, ref_points[dom.contains(ref_points)], bins)
        checks["samples_vs_mitsuba"] = wc.homogeneity_check(observed, reference_observed)
    checks["hard_inputs"] = wc.hard_inputs_check(dom, hard_variants or {"": (sample, pdf)})
    checks["throughput"] = throughput_check(sample, native_run, reference, judged=judge_throughput)
    return WarpResult(name, params, domain, checks, observed, cells.values * samples,
                      reference_observed, time.perf_counter() - start, seed, bins)


def equal_probability_cells(dom: Domain, pdf: wc.Pdf, samples: int,
                            *point_sets: np.ndarray) -> tuple[Bins, CellIntegrals]:
    """The chi-square cells of `pdf` for `samples` samples, as fine as the precision of the samples in
    `point_sets` allows (see warp_bins), and the pdf's integral over each."""
    bins = equal_probability_bins(wc.parameter_density(dom, pdf), HISTOGRAM_RES, samples, sample_quantum(*point_sets))
    return bins, wc.expected_probabilities(dom, pdf, bins)


def decide(results: list[WarpResult], alpha: float = SIGNIFICANCE) -> float:
    """Decide every statistical check of a run at the Sidak level over all of them; returns that level."""
    tests = [c for r in results for c in r.checks.values() if c.p_value is not None]
    level = sidak_level(alpha, len(tests))
    for c in tests:
        c.decide(level)
    return level


def check_warp(sample: Callable, pdf: Callable, domain: str, params: Any = None, seed: int = 0,
               *, args: tuple = (), samples: int = WARP_SAMPLES, reference: WarpFunctions | None = None,
               name: str = "user warp", input_dtype: Any = None) -> WarpResult:
    """Check a warp given as Python functions; see the module docstring.

    sample: (N, 2) uniforms in [0,1)^2 -> (N, 2) or (N, 3) points; pdf: points -> (N,) densities, or
    one value for a constant density. Either may be a numpy function (float32 results are fine) or a
    Mitsuba/Dr.Jit function passed as it is, e.g. mi.warp.square_to_beckmann (needs a vectorised
    variant such as llvm_ad_rgb; see warp_adapters). Mitsuba's pdfs do not test the domain: pass
    `warp_adapters.masked_to_domain(pdf, domain)` for them.
    `domain` is "square" ([0,1]^2), "tent" ([-1,1]^2), "disk", "sphere" or "hemisphere".
    `args`: extra positional arguments passed on to both functions after the array (default none),
    e.g. args=(0.3,) for Beckmann's alpha. `params` is only a label recorded in the result (default:
    `args`, if any). `samples`: samples for the statistical checks (default WARP_SAMPLES).
    `input_dtype`: the precision `sample` receives its uniforms in (np.float32 for a float32 warp: it gets
    float32 uniforms in [0, 1), and the hard inputs judge u as it sees them; default float64, or float32 for
    a Dr.Jit function).
    Raises ValueError when a function returns the wrong shape.
    """
    if params is None and args:
        params = list(args)
    result = evaluate_warp(NumpySampler(sample, args, input_dtype), NumpyPdf(pdf, args), domain, name=name,
                           params=params,
                           seed=seed, samples=samples, reference=reference)
    decide([result])
    return result
