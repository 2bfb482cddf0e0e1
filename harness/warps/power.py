"""How small a defect each warp check detects: power at the matrix's budget, by simulation with planted defects.

For a warp's cell probabilities p (its expected counts / N), the budget N and the per-test level, a defect of
size x is planted in p and the check is replayed on multinomial draws (POWER_REPLICATIONS of them, seeded);
the figure is the smallest x detected in POWER_TARGET of them. The halves of a defect split the cells by
their cumulative mass in row-major (s, then t) order: with equal-probability cells, the lower half of the
rows in s.

* chi2, "pdf_half": the pdf is wrong by (1 + eps) on one half of the mass and by the factor that keeps its
  integral 1 on the other (1 - eps for equal halves); the samples are right.
* chi2, "mass_moved": the sampler moves a fraction delta of all samples from one half into the other
  (proportionally to p on both sides); the pdf is right.
* samples_vs_mitsuba, "mass_moved": the same sampler defect, found by the homogeneity test of N samples of
  the tested engine against N of the reference.
* samples_vs_target, "mass_moved": the same sampler defect, found by the chi-square against the target's cells
  (the chi2 case, with the target's cell probabilities).

The noncentral chi-square gives a first estimate; simulation brackets it and bisects on a log scale.
Deterministic checks get their exact figure. Results are cached in CACHE_PATH, keyed by warp, samples,
cells, level and FORMAT_VERSION, and checked against a digest of p.
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Callable

import numpy as np

from harness.statistics.chi2 import goodness_of_fit_batch, homogeneity_batch
from harness.results import write_json
from harness.statistics.constants import (MIN_EXPECTED, NORMALISATION_TOLERANCE, PDF_RELATIVE_TOLERANCE, POWER_REPLICATIONS,
                           POWER_TARGET)

#: Bump when the simulation or its output changes: older cache entries are then recomputed.
FORMAT_VERSION = 1
#: Where simulated figures are kept between runs (relative to the working directory, like results/).
CACHE_PATH = Path("results/.cache/warp_power.json")
#: Defect sizes searched (relative pdf error, fraction of mass moved).
SEARCH_RANGE = (1e-4, 1.0)
#: Simulated bisection steps on a log scale inside the bracket around the noncentral estimate.
_BISECTIONS = 4
_BRACKET = 1.15

_DESCRIPTIONS = {
    "pdf_half": "pdf too high by this fraction on half of the mass (cells lower in s), too low on the other half",
    "mass_moved": "sampler moving this fraction of all samples from one half of the mass to the other",
}


@dataclass
class Power:
    """The smallest defect of one kind that a check detects in POWER_TARGET of replications.

    detects_90: defect size (a fraction: relative pdf error, mass moved, integral error); None when no
    number applies, or when no defect up to SEARCH_RANGE[1] is detected. method: "simulation" or "exact".
    """

    defect: str
    detects_90: float | None
    description: str
    method: str = "simulation"
    replications: int = 0
    #: Fraction of replications detecting the defect at detects_90 (simulation only).
    power_at_figure: float | None = None
    #: The noncentral chi-square's estimate of detects_90, before simulation.
    noncentral_estimate: float | None = None

    def to_json(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if v is not None and (k != "replications" or v)}


def lower_half(p: np.ndarray) -> np.ndarray:
    """Cells whose mid cumulative mass, in row-major order, is below half: a mask of p's shape."""
    flat = np.ravel(p) / np.sum(p)
    cum = np.cumsum(flat) - flat / 2
    return (cum < 0.5).reshape(np.shape(p))


def pdf_half_defect(p: np.ndarray, eps: float) -> np.ndarray:
    """p times (1 + eps) on the lower half, and on the other half by the factor keeping the total."""
    a = lower_half(p)
    share = p[a].sum() / p.sum()
    return np.where(a, p * (1 + eps), p * (1 - eps * share / (1 - share)))


def mass_moved_defect(p: np.ndarray, delta: float) -> np.ndarray:
    """p with a fraction delta of the total moved from the lower half to the upper one, proportionally."""
    a = lower_half(p)
    share = p[a].sum() / p.sum()
    return np.where(a, p * (1 - delta / share), p * (1 + delta / (1 - share))) if share > delta else p * np.nan


def _draw(q: np.ndarray, samples: int, replications: int, seed: int) -> np.ndarray:
    """Multinomial counts (replications, cells) from probabilities q (normalised here)."""
    rng = np.random.default_rng(seed)
    return rng.multinomial(samples, np.ravel(q) / np.sum(q), size=replications).astype(float)


@dataclass
class _Case:
    """One defect of one check: how to replay the check on a defect of size x."""

    defect: str
    detected: Callable[[float], np.ndarray]  # x -> rejections per replication (bool array)
    noncentrality: Callable[[float], float]  # x -> lambda of the statistic
    dof: int


def _cases(p: np.ndarray, samples: int, level: float, replications: int, seed: int,
           reference: bool) -> dict[str, list[_Case]]:
    p = np.ravel(p) / np.sum(p)
    dof = _dof(p, samples)
    truth = _draw(p, samples, replications, seed)

    def pdf_half(x: float) -> np.ndarray:
        return goodness_of_fit_batch(truth, samples * pdf_half_defect(p, x)).p_values < level

    def moved_gof(x: float) -> np.ndarray:
        q = mass_moved_defect(p, x)
        return goodness_of_fit_batch(_draw(q, samples, replications, seed + 1), samples * p).p_values < level

    def moved_homogeneity(x: float) -> np.ndarray:
        q = mass_moved_defect(p, x)
        return homogeneity_batch(_draw(q, samples, replications, seed + 1), truth).p_values < level

    def lam_gof(claim: Callable[[float], np.ndarray], drawn: Callable[[float], np.ndarray]) -> Callable:
        return lambda x: float(samples * np.sum((drawn(x) - claim(x)) ** 2 / claim(x)))

    same = lambda x: p  # noqa: E731
    cases = {"chi2": [
        _Case("pdf_half", pdf_half, lam_gof(lambda x: pdf_half_defect(p, x), same), dof),
        _Case("mass_moved", moved_gof, _moved_noncentrality(p, samples), dof),
    ]}
    if reference:
        cases["samples_vs_mitsuba"] = [_Case("mass_moved", moved_homogeneity, _moved_noncentrality(p, samples / 2),
                                             dof)]
    return cases


def _moved_noncentrality(p: np.ndarray, scale: float) -> Callable[[float], float]:
    """x -> the noncentrality of a chi-square in cells of probabilities p (normalised) when a sampler moves a
    fraction x of the mass (mass_moved_defect): `scale` the samples against p, half of each side's against as many
    of a correct sampler."""
    return lambda x: float(scale * np.sum((mass_moved_defect(p, x) - p) ** 2 / p))


def _dof(p: np.ndarray, samples: int) -> int:
    """Degrees of freedom of the chi-square in cells of probabilities p (normalised): cells below MIN_EXPECTED
    pooled into one."""
    low = samples * p < MIN_EXPECTED
    return max(int((~low).sum()) + int(samples * p[low].sum() >= MIN_EXPECTED) - 1, 1)


def noncentral_mass_moved(p: np.ndarray, samples: int, level: float, two_sample: bool = False) -> float | None:
    """The fraction of all samples moved from one half of the mass to the other (mass_moved_defect) that the
    chi-square of `samples` samples in cells of probabilities p finds POWER_TARGET of the time at `level`, by the
    noncentral chi-square alone (no simulation): against p itself, or (`two_sample`) against as many samples of a
    correct sampler. None where no defect in SEARCH_RANGE is found so often. Cells of probability 0 are left out:
    a defect moved in proportion to p puts nothing there."""
    p = np.ravel(np.asarray(p, dtype=float))
    p = p[p > 0] / np.sum(p)
    if len(p) < 2:
        return None
    noncentrality = _moved_noncentrality(p, samples / 2 if two_sample else samples)
    return _noncentral_estimate(_Case("mass_moved", lambda x: np.zeros(0, bool), noncentrality, _dof(p, samples)), level)


def _noncentral_estimate(case: _Case, level: float) -> float | None:
    """The defect size at which the noncentral chi-square has power POWER_TARGET (None: beyond the range)."""
    with np.errstate(divide="ignore", invalid="ignore"):  # cells of probability 0 give NaN terms: no estimate
        return _estimate(case, level)


def _estimate(case: _Case, level: float) -> float | None:
    # Imported here, where a power is searched (its cache usually answers): scipy.stats costs every harness
    # process most of a second to import.
    from scipy import optimize as spo
    from scipy import stats as sps

    critical = sps.chi2.isf(level, case.dof)
    lo, hi = np.log(SEARCH_RANGE[0]), np.log(min(SEARCH_RANGE[1], 0.49))

    def gap(logx: float) -> float:
        lam = case.noncentrality(float(np.exp(logx)))
        return float(sps.ncx2.sf(critical, case.dof, lam)) - POWER_TARGET if np.isfinite(lam) else 1.0
    if gap(hi) < 0:
        return None
    if gap(lo) >= 0:
        return SEARCH_RANGE[0]
    return float(np.exp(spo.brentq(gap, lo, hi, xtol=1e-3)))


def smallest_detected(case: _Case, level: float, replications: int) -> Power:
    """Bracket the noncentral estimate by simulation and bisect on a log scale; see the module docstring."""
    estimate = _noncentral_estimate(case, level)
    described = dict(defect=case.defect, description=_DESCRIPTIONS[case.defect], replications=replications)
    if estimate is None:
        return Power(detects_90=None, noncentral_estimate=None, **described)
    power = {}

    def rate(x: float) -> float:
        if x not in power:
            power[x] = float(np.mean(case.detected(x)))
        return power[x]
    lo, hi = max(estimate / _BRACKET, SEARCH_RANGE[0]), min(estimate * _BRACKET, SEARCH_RANGE[1])
    while rate(hi) < POWER_TARGET and hi < SEARCH_RANGE[1]:
        lo, hi = hi, min(hi * _BRACKET ** 2, SEARCH_RANGE[1])
    if rate(hi) < POWER_TARGET:
        return Power(detects_90=None, noncentral_estimate=estimate, **described)
    while rate(lo) >= POWER_TARGET and lo > SEARCH_RANGE[0]:
        lo, hi = max(lo / _BRACKET ** 2, SEARCH_RANGE[0]), lo
    for _ in range(_BISECTIONS):
        mid = float(np.sqrt(lo * hi))
        lo, hi = (lo, mid) if rate(mid) >= POWER_TARGET else (mid, hi)
    return Power(detects_90=hi, power_at_figure=rate(hi), noncentral_estimate=estimate, **described)


def simulated_powers(p: np.ndarray, samples: int, level: float, reference: bool,
                     replications: int = POWER_REPLICATIONS, seed: int = 0) -> dict[str, list[Power]]:
    """Simulated figures of the statistical checks for cell probabilities p (any shape, any positive scale)."""
    cases = _cases(np.asarray(p, dtype=float), samples, level, replications, seed, reference)
    return {check: [smallest_detected(c, level, replications) for c in found] for check, found in cases.items()}


def exact_powers() -> dict[str, list[Power]]:
    """What the deterministic checks detect, by construction."""
    return {
        "normalisation": [Power("normalisation", NORMALISATION_TOLERANCE,
                                "pdf whose integral over the domain is off by more than this", "exact")],
        "pdf_vs_mitsuba": [Power("pdf_relative", PDF_RELATIVE_TOLERANCE,
                                 "relative pdf difference from Mitsuba at any probe point, beyond the reference's "
                                 "own float32 rounding", "exact")],
        "pdf_vs_target": [Power("pdf_relative", PDF_RELATIVE_TOLERANCE,
                                "relative pdf difference from the closed form of the warp's name at any probe point, "
                                "beyond its change under one-ulp moves of the point", "exact")],
        "domain": [Power("any", None, "any sample outside the domain, pdf NaN or < 0 at a sample, pdf > 0 at "
                         "a probe outside the domain", "exact")],
        "hard_inputs": [Power("any", None, "any NaN/Inf sample or pdf not finite and > 0 on the hard inputs",
                              "exact")],
        "throughput": [Power("rate", None, "a rate below the throughput floor", "exact")],
    }


def digest(p: np.ndarray) -> str:
    """A short fingerprint of cell probabilities (to 1e-4 of their mean), so that a cached figure follows the pdf."""
    q = np.round(np.asarray(p, dtype=float) * (np.size(p) / np.sum(p)), 4)
    return hashlib.sha1(np.ascontiguousarray(q).tobytes() + str(q.shape).encode()).hexdigest()[:16]


def cache_key(warp_key: str, samples: int, shape: tuple[int, ...], level: float) -> str:
    return f"{warp_key}|{samples}|{'x'.join(map(str, shape))}|{level:.3g}|v{FORMAT_VERSION}"


def _read_cache(path: Path) -> dict:
    try:
        data = json.loads(path.read_text())
        return data if isinstance(data, dict) else {}
    except (OSError, ValueError):
        return {}


def _simulated(p: np.ndarray, samples: int, level: float, reference: bool, memo: dict) -> dict[str, list[dict]]:
    """simulated_powers of cell probabilities p as JSON, shared within a run by warps of identical cells."""
    key = f"{digest(p)}|{samples}|{level:.3g}"
    found = memo.get(key)
    if found is None or (reference and "samples_vs_mitsuba" not in found):
        sim = simulated_powers(p, samples, level, reference)
        memo[key] = found = {c: [f.to_json() for f in fs] for c, fs in sim.items()}
    return {c: fs for c, fs in found.items() if reference or c != "samples_vs_mitsuba"}


def _cached(cache: dict, key: str, p: np.ndarray, reference: bool, compute: Callable[[], dict]) -> tuple[dict, bool]:
    """The cached figures of `key` if they are of these cell probabilities; else computed. Returns (figures,
    whether the cache changed)."""
    entry = cache.get(key)
    d = digest(p)
    if entry and entry.get("digest") == d and entry.get("reference") == reference:
        return entry["figures"], False
    cache[key] = {"digest": d, "reference": reference, "figures": compute()}
    return cache[key]["figures"], True


def _usable(p: np.ndarray | None) -> bool:
    return p is not None and bool(np.all(np.isfinite(p)) and np.all(p >= 0) and p.sum() > 0)


def attach_power(results: list, warp_keys: list[str], samples: int, level: float,
                 cache_path: Path | None = CACHE_PATH) -> None:
    """Put each check's figures into its details["power"] (a list of Power.to_json()), for every result.

    results: WarpResults of one run (expected counts = N * cell probabilities, and the target's, if any);
    warp_keys: their keys; cache_path: JSON cache of simulated figures (None: no cache). Warps with identical
    cells share one simulation within a run (a correct warp's cells and its target's are alike).
    """
    cache = _read_cache(cache_path) if cache_path else {}
    memo: dict[str, dict] = {}
    changed = False
    for r, key in zip(results, warp_keys):
        figures: dict[str, list[Power | dict]] = dict(exact_powers())
        p = np.asarray(r.expected, dtype=float)
        if _usable(p):
            reference = r.reference_observed is not None
            found, new = _cached(cache, cache_key(key, samples, p.shape, level), p, reference,
                                 lambda: _simulated(p, samples, level, reference, memo))
            figures.update(found)
            changed |= new
        q = getattr(r, "target_expected", None)
        if _usable(q):
            q = np.asarray(q, dtype=float)
            found, new = _cached(cache, cache_key(key + "@target", samples, q.shape, level), q, False,
                                 lambda: {"samples_vs_target": [f for f in _simulated(q, samples, level, False, memo)
                                                                ["chi2"] if f["defect"] == "mass_moved"]})
            figures.update(found)
            changed |= new
        for name, check in r.checks.items():
            if name in figures and not check.skipped:
                check.details["power"] = [f.to_json() if isinstance(f, Power) else f for f in figures[name]]
    if cache_path and changed:
        write_json(cache_path, cache)
