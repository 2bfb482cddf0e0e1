"""Warp conformance: a sampler checked against its own pdf, against the closed form its name promises, and
against a reference implementation.

Public API::

    result = check_warp(sample, pdf, "disk", seed=0)
    result.passed, result.checks["chi2"].figure

`sample` maps an (N, 2) array of uniforms in [0,1)^2 to (N, 2) or (N, 3)
points, `pdf` maps such points to (N,) densities (w.r.t. area on 2D domains,
solid angle on the sphere and hemisphere). A warp of a name mcval knows (the
matrix's warps, harness.warps.targets) is also judged against that name's closed
form; checks that need a reference implementation are skipped unless one is given. check_warp also takes float32
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
from harness.warps.check_result import CheckResult, skipped
from harness.warps.hard_inputs import hard_inputs_check
from harness.warps.pdf_agreement import pdf_agreement_check
from harness.warps.domains import get_domain
from harness.engines.base import WarpFunctions
from harness.statistics.constants import SIGNIFICANCE, WARP_SAMPLES, sidak_level
from harness.warps.adapters import NumpyPdf, NumpySampler
from harness.warps.bins import Bins, sample_quantum
from harness.warps.target_checks import PDF_PROBES, judged_by_own_pdf, target_checks
from harness.warps.targets import Target, known_names, target_for
from harness.warps.throughput import throughput_check

#: The checks, in the order reports show them.
CHECK_NAMES = ("chi2", "normalisation", "domain", "pdf_vs_target", "samples_vs_target", "pdf_vs_mitsuba",
               "samples_vs_mitsuba", "hard_inputs", "throughput")


@dataclass
class WarpResult:
    """Every check of one warp (with one parameter value), and the histograms behind them."""

    warp: str
    params: Any
    domain: str
    checks: dict[str, CheckResult]
    #: Histograms over the parameter square: our samples, the pdf's expectation, the reference's samples.
    observed: np.ndarray
    expected: np.ndarray
    reference_observed: np.ndarray | None
    seconds: float
    seed: int
    #: The histograms' cells (equal-probability in the pdf's marginals; see warp_bins).
    bins: Bins | None = None
    #: The closed form the warp's name promises (None: judged against its own pdf only), our samples in its
    #: equal-probability cells, the counts it expects there, and those cells.
    target: Target | None = None
    target_observed: np.ndarray | None = None
    target_expected: np.ndarray | None = None
    target_bins: Bins | None = None
    #: Why no check could run, in one line (a user's library that crashed, exited or hung in this warp).
    failure: str | None = None

    @property
    def passed(self) -> bool:
        return self.failure is None and all(bool(c.passed) for c in self.checks.values() if not c.skipped)

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

    @property
    def judged_against(self) -> str:
        """What the warp was judged against, in words."""
        if self.target is None:
            return "its own pdf only (no closed form known for its name)"
        return f"{self.target.label} (its name) and its own pdf"

    def to_json(self) -> dict[str, Any]:
        return {"warp": self.warp, "params": self.params, "domain": self.domain, "pass": self.passed,
                "verdict": self.verdict, "warnings": self.warnings, "seed": self.seed, "seconds": self.seconds,
                "target": None if self.target is None else self.target.label, "judged_against": self.judged_against,
                "checks": {k: c.to_json() for k, c in self.checks.items()},
                **({"failure": self.failure} if self.failure else {})}


def failed_warp(name: str, params: Any, domain: str, seed: int, reason: str) -> WarpResult:
    """The result of a warp whose checks could not run: it fails with `reason`, and has no histograms."""
    empty = np.zeros((0, 0))
    return WarpResult(name, params, domain, {}, empty, empty, None, 0.0, seed, failure=reason)


def format_params(params: Any) -> str:
    if isinstance(params, dict):
        return ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in params.items())
    return str(params)


def evaluate_warp(sample: wc.Sampler, pdf: wc.Pdf, domain: str, *, name: str = "user warp",
                  params: Any = None, seed: int = 0, samples: int = WARP_SAMPLES,
                  reference: WarpFunctions | None = None, target: Target | None = None, native_run=None,
                  hard_variants: dict[str, tuple[wc.Sampler, wc.Pdf]] | None = None,
                  judge_throughput: bool = True, timed: bool = True) -> WarpResult:
    """Run every check; statistical ones are left undecided (see `decide`). A sampler taking float32 (its
    `input_dtype`) gets float32 uniforms, all in [0, 1); `target`: the closed form the warp's name promises
    (harness.warps.targets; None: judged against its own pdf only); `judge_throughput` False reports the
    throughput without a floor (a user's code); `timed` False skips the throughput, which no seed changes
    (a second seed of the same warp)."""
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
    tested = points[inside]
    # Samples that never reach a histogram: outside the domain, and of those NaN/Inf.
    lost = (int(np.count_nonzero(~inside)), int(np.count_nonzero(~np.all(np.isfinite(points), axis=1))))
    ref_points = None if reference is None else wc.as_points(
        reference.sample(np.random.default_rng([seed, 1]).random((samples, 2))), samples, "reference sample")
    quantum = sample_quantum(*((tested,) if ref_points is None else (tested, ref_points)))
    bins, cells = wc.equal_probability_cells(dom, pdf, samples, quantum)
    param = dom.to_param(tested)
    observed = wc.histogram(dom, tested, bins, param)

    checks = {
        "chi2": wc.chi2_check(observed, cells.values, lost[0], bins, lost[1]),
        "normalisation": wc.normalisation_check(float(cells.values.sum()), cells.error),
        "domain": wc.domain_check(dom, points, pdf, rng, u, getattr(sample, "input_dtype", np.float64)),
    }
    by_name = (judged_by_own_pdf(name) if target is None else
               target_checks(dom, target, pdf, tested, param, lost, samples, quantum, (bins, observed)))
    checks.update(by_name.checks)
    reference_observed = None
    if reference is None:
        checks["pdf_vs_mitsuba"] = skipped("no reference implementation")
        checks["samples_vs_mitsuba"] = skipped("no reference implementation")
    else:
        ref_inside = ref_points[dom.inside(ref_points)]
        # Where our samples are missing (NaN, outside), the reference's own show where its mass is.
        probe = np.concatenate([tested[:PDF_PROBES], ref_inside[:max(PDF_PROBES - len(tested), 0)]])
        checks["pdf_vs_mitsuba"] = pdf_agreement_check(np.concatenate([probe, wc.parameter_grid(dom)]), pdf,
                                                          reference.pdf, "the reference pdf")
        reference_observed = wc.histogram(dom, ref_inside, bins)
        checks["samples_vs_mitsuba"] = wc.homogeneity_check(observed, reference_observed, *lost)
    checks["hard_inputs"] = hard_inputs_check(dom, hard_variants or {"": (sample, pdf)})
    checks["throughput"] = (throughput_check(sample, native_run, reference, judged=judge_throughput) if timed
                            else skipped("not timed in this run"))
    return WarpResult(name, params, domain, checks, observed, cells.values * samples,
                      reference_observed, time.perf_counter() - start, seed, bins, target, by_name.observed,
                      by_name.expected, by_name.bins)


def decide(results: list[WarpResult], alpha: float = SIGNIFICANCE) -> float:
    """Decide every statistical check of a run at the Sidak level over all of them; returns that level."""
    tests = [c for r in results for c in r.checks.values() if c.p_value is not None]
    level = sidak_level(alpha, len(tests))
    for c in tests:
        c.decide(level)
    return level


def _alpha(params: Any, args: tuple) -> float | None:
    """Beckmann's roughness as a caller gives it: params {"alpha": a}, or a single number in args."""
    if isinstance(params, dict) and isinstance(params.get("alpha"), (int, float)):
        return float(params["alpha"])
    if len(args) == 1 and isinstance(args[0], (int, float)) and not isinstance(args[0], bool):
        return float(args[0])
    return None


def resolve_target(target: str | None, name: str, domain: str, params: Any = None, args: tuple = ()) -> Target | None:
    """The closed form a warp is judged against: `target`'s (a name mcval must know), else `name`'s if mcval
    knows it, else None. Raises ValueError for an unknown `target` or one of another domain."""
    found = target_for(target if target is not None else name, _alpha(params, args))
    if found is None and target is not None:
        raise ValueError(f"no closed form known for target {target!r}: known are {', '.join(known_names())}")
    if found is not None and found.domain != domain:
        raise ValueError(f"{found.warp} is a warp to the {found.domain} domain, not to the {domain}")
    return found


def check_warp(sample: Callable, pdf: Callable, domain: str, params: Any = None, seed: int = 0,
               *, args: tuple = (), samples: int = WARP_SAMPLES, reference: WarpFunctions | None = None,
               name: str = "user warp", target: str | None = None, input_dtype: Any = None) -> WarpResult:
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
    `target`: the warp this one claims to be, by Mitsuba's name or its short form ("tent", "uniform_disk",
    "square_to_cosine_hemisphere", "beckmann:0.3"; Beckmann's alpha may come from params={"alpha": a} or
    args=(a,) instead): its samples are then tested against that warp's closed-form density and its pdf
    compared with it (pdf_vs_target, samples_vs_target). Default: `name`, when mcval knows it; a warp of any
    other name is judged against its own pdf only, and its result says so (`judged_against`).
    Raises ValueError when a function returns the wrong shape, for an unknown `target`, a target of another
    domain, and Beckmann's without its alpha.
    """
    found = resolve_target(target, name, domain, params, args)
    if params is None and args:
        params = list(args)
    result = evaluate_warp(NumpySampler(sample, args, input_dtype), NumpyPdf(pdf, args), domain, name=name,
                           params=params, seed=seed, samples=samples, reference=reference, target=found)
    decide([result])
    return result
