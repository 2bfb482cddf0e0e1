"""The checks of one BSDF at one incident direction wi, each a CheckResult (harness/warps/check_result.py):

- sampling: the sampled directions against the BSDF's own pdf, by chi-square on the sphere in cells of equal
  expected count, the samples that failed (weight and pdf 0) counted in a cell of their own whose expected
  share is 1 minus the pdf's integral;
- normalisation: the pdf integrates to 1 minus the share of failed samples;
- weight: every sample's weight is value / pdf at its direction, and its pdf the pdf's value there (the check
  Mitsuba's chi2 adapter does not make: it counts a sample whatever its weight);
- energy: the directional albedo E[weight] is at most 1 (one-sided), with the smallest excess it finds 90 % of
  the time;
- reciprocity: value / |cos theta_o| is symmetric in wi and wo where both are above the surface.

Statistical checks (sampling, energy) carry a p-value, decided at the run's level."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.engines.base import BsdfFunctions
from harness.statistics.constants import NORMALISATION_TOLERANCE
from harness.statistics.distributions import norm_isf, norm_ppf, norm_sf
from harness.warps.bins import Bins, sample_quantum
from harness.warps.check_result import CheckResult, not_judged
from harness.warps.checks import chi2_check, equal_probability_cells, histogram, normalisation_check
from harness.warps.domains import SPHERE

#: Relative difference allowed between a sample's weight and value / pdf (and its pdf and the pdf's): float32
#: arithmetic reaches a few ulps; any missing factor (a cosine, 1/pi, a Jacobian) is far beyond.
WEIGHT_TOLERANCE = 1e-3
#: A few samples may be off by more than WEIGHT_TOLERANCE, up to this much: at most this share of them (and 1).
ROUNDING_TOLERANCE, ROUNDING_SHARE = 1e-2, 1e-4
#: Relative difference allowed between value / |cos theta_o| and its reciprocal.
RECIPROCITY_TOLERANCE = 1e-3
#: Power of the energy check's stated smallest excess.
POWER = 0.9
#: Albedo above 1 the energy check allows: float32 rounding of a lossless BSDF's weights (a glass's R + T,
#: eta_ti^2 rounded) reaches about 1e-7; any lost or added factor is far beyond.
ENERGY_ROUNDING = 1e-6
#: The largest error of the pdf's cell integrals (as the cubature estimates it) at which the chi-square is judged:
#: beyond it the expected counts are not known well enough (a lobe narrower than the cubature resolves).
INTEGRATION_LIMIT = 1e-3


@dataclass(frozen=True)
class Draw:
    """`n` samples of the BSDF at wi: the sampled directions, weights and pdfs (float64)."""

    wi: np.ndarray
    wo: np.ndarray
    weight: np.ndarray
    pdf: np.ndarray

    @property
    def failed(self) -> np.ndarray:
        """The samples that drew nothing: weight and pdf 0 (as the ABI says)."""
        return (self.pdf == 0) & (self.weight == 0)

    @property
    def delta(self) -> np.ndarray:
        """The samples on a delta lobe (a mirror's, a smooth glass's): an infinite pdf (as the ABI says)."""
        return np.isposinf(self.pdf)

    @property
    def smooth(self) -> np.ndarray:
        """The samples drawn from a density: neither failed nor on a delta lobe."""
        return ~self.failed & ~self.delta


def incident(theta_degrees: float, below: bool = False) -> np.ndarray:
    """The unit wi at polar angle theta from the normal, in the xz plane (the BSDFs are isotropic): above the
    surface up to 90 degrees, below it beyond; `below`: mirrored under the surface (for the BSDFs that
    transmit)."""
    t = np.radians(theta_degrees)
    return np.array([np.sin(t), 0.0, -np.cos(t) if below else np.cos(t)])


def draw(bsdf: BsdfFunctions, wi: np.ndarray, samples: int, seed: int | list[int]) -> Draw:
    u = np.random.default_rng(seed).random((samples, 3), dtype=np.float32).astype(np.float64)
    wo, weight, pdf = bsdf.sample(np.tile(wi, (samples, 1)), u)
    return Draw(wi, wo, weight, pdf)


def _pdf_at(bsdf: BsdfFunctions, wi: np.ndarray):
    return lambda wo: bsdf.pdf(np.tile(wi, (len(wo), 1)), wo)


@dataclass(frozen=True)
class CellCounts:
    """The drawn directions per cell of the sampling check and the pdf's expected counts there, (rows, cols)."""

    observed: np.ndarray
    expected: np.ndarray


def sampling_checks(bsdf: BsdfFunctions, d: Draw,
                    pilot: Draw | None = None) -> tuple[CheckResult, CheckResult, Bins, CellCounts | None]:
    """The chi-square of the sampled directions against the pdf, the pdf's normalisation (see the module), the
    cells of that chi-square (for the reference's samples: harness/bsdfs/reference.py) and its counts (None where
    nothing was drawn from a density). Samples on a delta lobe count with the failed ones: the pdf describes the
    rest. `pilot`: samples drawn apart from `d`, whose quantiles give the cells (else the pdf's)."""
    n = len(d.wo)
    failed = ~d.smooth
    drawn = d.wo[~failed]
    pilot_points = None
    if pilot is not None:
        pilot_points = pilot.wo[pilot.smooth]
        pilot_points = pilot_points[SPHERE.inside(pilot_points)]
    bins, integrals = equal_probability_cells(SPHERE, _pdf_at(bsdf, d.wi), n, sample_quantum(drawn), pilot_points)
    probabilities = np.asarray(integrals.values, np.float64).ravel()
    integral = float(probabilities.sum())
    share = float(np.count_nonzero(failed)) / n
    if not d.delta.any() and not len(drawn):  # a BSDF that draws nothing passes nothing: it judged nothing
        return (not_judged(f"no sample was drawn: all {n} failed (weight and pdf 0)"),
                normalisation_check(integral + share, integrals.error), bins, None)
    if integral == 0 and not len(drawn):  # a mirror: every sample on its delta lobe, and no density anywhere
        summary = f"no density: pdf() is 0 everywhere, and all {n} samples are on a delta lobe or failed"
        return (CheckResult(None, 0.0, summary, p_value=1.0), CheckResult(True, 0.0, summary), bins, None)
    # Within 5 standard deviations of the failed share, the integration's own tolerance and its estimated error.
    slack = NORMALISATION_TOLERANCE + 5.0 * np.sqrt(max(share * (1 - share), 1.0 / n) / n) + integrals.error
    if abs(integral + share - 1.0) <= slack:
        normalisation = CheckResult(True, integral, f"integral = {integral:.6f}, {share:.4%} of samples failed "
                                    "or on a delta lobe",
                                    details={"tolerance": slack, "integration_error": integrals.error})
    else:
        normalisation = normalisation_check(integral + share, integrals.error)
    # The failed samples are one more cell, expected at 1 - the pdf's integral; a drawn sample that is no unit
    # direction never reaches a cell and fails the check as a sample outside the domain.
    inside = SPHERE.inside(drawn)
    cells = histogram(SPHERE, drawn[inside], bins)
    observed = np.append(cells.ravel(), np.count_nonzero(failed))
    sampling = chi2_check(observed, np.append(probabilities, max(1.0 - integral, 0.0)),
                          int(np.count_nonzero(~inside)), bins, int(np.count_nonzero(~np.all(np.isfinite(drawn), axis=1))))
    sampling.details.update(failed_samples=int(np.count_nonzero(failed)), integration_error=integrals.error)
    if sampling.hard_failure is None and integrals.error > INTEGRATION_LIMIT:
        sampling = not_judged(f"the pdf's cell integrals are uncertain to {integrals.error:.2g} (a lobe narrower than "
                              f"the cubature resolves; at most {INTEGRATION_LIMIT:g} is judged)", **sampling.details)
    return sampling, normalisation, bins, CellCounts(cells, probabilities.reshape(cells.shape) * n)


def _relative(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):  # inf against inf is NaN: the callers flag infinities themselves
        return np.abs(a - b) / np.maximum(np.maximum(np.abs(a), np.abs(b)), 1e-30)


def _rounding_only(weight, expected, sampled_pdf, pdf, bad: np.ndarray) -> int:
    """How many samples are off, where they are so few (ROUNDING_SHARE of the samples, at least 1) and so near
    (within ROUNDING_TOLERANCE, finite) that float32 rounding explains them; else 0. Near a glass's critical angle
    the half vector recomputed from a float32 wo moves by more than 1e-3 (Mitsuba's GGX glass: 2 samples in
    200,000 at 1.2e-3); a missing factor is off at most samples, and by far more."""
    count = int(bad.sum())
    if not count or count > max(1, ROUNDING_SHARE * len(bad)):
        return 0
    with np.errstate(invalid="ignore"):
        off = np.maximum(_relative(weight[bad], expected[bad]), _relative(sampled_pdf[bad], pdf[bad]))
    return count if np.all(np.isfinite(off)) and np.all(off <= ROUNDING_TOLERANCE) else 0


def weight_check(bsdf: BsdfFunctions, d: Draw) -> CheckResult:
    """Every sample's weight is value / pdf at its direction and its pdf the pdf's value there; a failed sample
    has weight 0 and a drawn one a finite, non-negative weight (a delta sample's weight has no value / pdf to
    match: only that)."""
    delta_weights = d.weight[d.delta]
    bad_delta = ~np.isfinite(delta_weights) | (delta_weights < 0)
    if bad_delta.any():
        return CheckResult(False, float(bad_delta.sum()), f"{int(bad_delta.sum())} samples on a delta lobe have a "
                           f"NaN, infinite or negative weight (e.g. {delta_weights[bad_delta][0]:.4g})",
                           details={"delta_samples": int(d.delta.sum()), "weight_off": int(bad_delta.sum())})
    drawn = d.smooth
    wi = np.tile(d.wi, (int(drawn.sum()), 1))
    value, pdf = bsdf.eval(wi, d.wo[drawn]), bsdf.pdf(wi, d.wo[drawn])
    weight, sampled_pdf = d.weight[drawn], d.pdf[drawn]
    with np.errstate(divide="ignore", invalid="ignore"):
        expected = np.where(pdf > 0, value / pdf, np.inf)
    # Where pdf() is 0 no weight is value / pdf (expected infinite: a NaN relative difference would let it by).
    bad_weight = ~np.isfinite(weight) | (weight < 0) | ~np.isfinite(expected) | \
        (_relative(weight, expected) > WEIGHT_TOLERANCE)
    bad_pdf = ~np.isfinite(sampled_pdf) | (_relative(sampled_pdf, pdf) > WEIGHT_TOLERANCE)
    details = {"samples": int(drawn.sum()), "weight_off": int(bad_weight.sum()), "pdf_off": int(bad_pdf.sum()),
               "tolerance": WEIGHT_TOLERANCE}
    rounding = _rounding_only(weight, expected, sampled_pdf, pdf, bad_weight | bad_pdf)
    if rounding:
        details["within_rounding"] = rounding
        bad_weight, bad_pdf = np.zeros_like(bad_weight), np.zeros_like(bad_pdf)
    if not (bad_weight.any() or bad_pdf.any()):
        on_delta = f"; {int(d.delta.sum())} on a delta lobe, each weight finite" if d.delta.any() else ""
        near = (f" ({rounding} within {ROUNDING_TOLERANCE:g} only: float32 rounding where wo is ill-conditioned)"
                if rounding else "")
        return CheckResult(True, 0.0, f"weight = value / pdf at all {int(drawn.sum())} samples{near}{on_delta}",
                           details=details)
    parts = []
    if bad_weight.any():
        k = int(np.flatnonzero(bad_weight)[0])
        ratio = weight[k] / expected[k] if np.isfinite(expected[k]) and expected[k] else float("nan")
        parts.append(f"{int(bad_weight.sum())} weights are not value / pdf (e.g. at cos theta_o = "
                     f"{d.wo[drawn][k, 2]:.3f}: weight {weight[k]:.4g}, value / pdf {expected[k]:.4g}, ratio {ratio:.4g})")
    if bad_pdf.any():
        k = int(np.flatnonzero(bad_pdf)[0])
        parts.append(f"{int(bad_pdf.sum())} sampled pdfs differ from pdf() (e.g. {sampled_pdf[k]:.4g} and {pdf[k]:.4g})")
    return CheckResult(False, float(bad_weight.sum() + bad_pdf.sum()), "; ".join(parts), details=details)


def flux_factors(d: Draw, eta: float | None) -> np.ndarray:
    """What turns each sample's weight into the share of energy it carries: 1, but (eta of wo's side / eta of
    wi's side)^2 for a sample that crosses an interface of relative index `eta` = int / ext (a weight in radiance
    carries the compression of the solid angle it crosses into: Mitsuba's radiance mode)."""
    if eta is None:
        return np.ones(len(d.wo))
    crossing = d.wo[:, 2] * d.wi[2] < 0
    ratio = eta if d.wi[2] > 0 else 1.0 / eta  # wo's side over wi's
    return np.where(crossing, ratio ** 2, 1.0)


def energy_check(d: Draw, level: float, eta: float | None = None) -> CheckResult:
    """E[weight] <= 1, one-sided: the p-value of the mean weight under an albedo of exactly 1. `level` (the run's
    per-test level) sets the stated smallest excess found with probability POWER. `eta`: the relative index of a
    BSDF that transmits, whose weights across it are counted as energy (flux_factors)."""
    w = np.where(d.failed, 0.0, d.weight * flux_factors(d, eta))
    if not np.all(np.isfinite(w)):
        hard = f"{int(np.count_nonzero(~np.isfinite(w)))} weights are NaN or infinite"
        return CheckResult(False, float("nan"), hard, p_value=0.0, hard_failure=hard)
    mean, se = float(w.mean()), float(w.std(ddof=1) / np.sqrt(len(w)))
    if se == 0:
        p = 1.0 if mean <= 1.0 + ENERGY_ROUNDING else 0.0
    else:
        p = float(norm_sf((mean - 1.0 - ENERGY_ROUNDING) / se))
    excess = float(ENERGY_ROUNDING + (norm_isf(level) + norm_ppf(POWER)) * se)
    details = {"albedo": mean, "standard_error": se, "detectable_excess": excess, "power": POWER}
    return CheckResult(None, mean, f"albedo {mean:.5f} ± {se:.2g}; p = {p:.3g} (finds an excess of {excess:.2g} "
                       f"{POWER:.0%} of the time)", p_value=p, details=details)


def reciprocity_check(bsdf: BsdfFunctions, pairs: int, seed: int) -> CheckResult:
    """value(wi, wo) / |cos theta_o| = value(wo, wi) / |cos theta_i| at `pairs` random pairs above the surface."""
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(2, pairs, 3))
    v[..., 2] = np.abs(v[..., 2]) + 1e-3
    wi, wo = v / np.linalg.norm(v, axis=-1, keepdims=True)
    there, back = bsdf.eval(wi, wo) / wo[:, 2], bsdf.eval(wo, wi) / wi[:, 2]
    off = ~np.isfinite(there) | ~np.isfinite(back) | (_relative(there, back) > RECIPROCITY_TOLERANCE) & \
        (np.maximum(np.abs(there), np.abs(back)) > 1e-6)
    details = {"pairs": pairs, "not_reciprocal": int(off.sum()), "tolerance": RECIPROCITY_TOLERANCE}
    if not off.any():
        return CheckResult(True, 0.0, f"reciprocal at all {pairs} pairs", details=details)
    k = int(np.flatnonzero(off)[0])
    return CheckResult(False, float(off.sum()), f"{int(off.sum())} of {pairs} pairs not reciprocal (e.g. cos theta_i "
                       f"= {wi[k, 2]:.3f}, cos theta_o = {wo[k, 2]:.3f}: f = {there[k]:.4g} one way, {back[k]:.4g} "
                       "the other)", details=details)
