"""The pdf against another at the same points: a reference implementation's (pdf_vs_mitsuba) or the closed form
of the warp's name (pdf_vs_target), within PDF_RELATIVE_TOLERANCE beyond the other's own float32 rounding."""
from __future__ import annotations

import numpy as np

from harness.statistics.constants import PDF_ABSOLUTE_FLOOR, PDF_RELATIVE_TOLERANCE
from harness.statistics.factors import name_factor
from harness.warps.check_result import CheckResult, not_judged
from harness.warps.checks import Pdf, as_values, factor_phrase


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


#: A pdf is a constant times the reference when it is at this share of the probe points at least (a pdf that
#: tests its support in float32 may differ at a point on the rim that the reference counts in).
CONSTANT_SHARE = 0.99


def _constant_factor(tested: np.ndarray, ref: np.ndarray, slack: np.ndarray) -> tuple[float, int, int] | None:
    """(c, n, m): tested = c * ref at n of the m probe points where the reference is above PDF_ABSOLUTE_FLOOR (within
    PDF_RELATIVE_TOLERANCE and c times the reference's rounding slack), n at least CONSTANT_SHARE of m; None if
    the two differ by more than a constant."""
    seen = ref > PDF_ABSOLUTE_FLOOR
    tested, ref, slack = tested[seen], ref[seen], slack[seen]
    if not len(tested):
        return None
    with np.errstate(invalid="ignore", over="ignore"):
        c = float(np.median(tested / ref))
        agree = int(np.count_nonzero(np.abs(tested - c * ref) - c * slack <= PDF_RELATIVE_TOLERANCE * c * ref))
    return (c, agree, len(tested)) if np.isfinite(c) and c > 0 and agree >= CONSTANT_SHARE * len(tested) else None


def pdf_agreement_check(points: np.ndarray, pdf: Pdf, reference_pdf: Pdf, reference: str = "the reference") -> CheckResult:
    """Our pdf equals the reference pdf at the same points inside the support.

    Allowed difference per point: PDF_RELATIVE_TOLERANCE of the reference value,
    plus twice the reference's own change under one-ulp moves of the point, plus PDF_ABSOLUTE_FLOOR (a float32
    pdf underflows to 0 where a float64 one is still 1e-35). A pdf that is a constant times the
    reference says so first, naming the factor when it is one (statistics.factors): "pdf = pi^2 x the
    reference: pi^2 too large". Not judged (a failure) when the reference is 0 at every point. `reference`:
    its name in the summary.
    """
    ref = as_values(reference_pdf(points), len(points), "reference pdf")
    inside = ref > 0
    if not inside.any():
        return not_judged(f"{reference} is 0 at all {len(points)} probe points", statistical=False,
                          points=0, tolerance=PDF_RELATIVE_TOLERANCE)
    points, ref = points[inside], ref[inside]
    tested = as_values(pdf(points), len(points), "pdf")
    slack = 2.0 * _rounding_sensitivity(points, reference_pdf)
    with np.errstate(invalid="ignore", over="ignore"):  # an infinite pdf is a difference of inf, not a warning
        diff = np.maximum(np.abs(tested - ref) - PDF_ABSOLUTE_FLOOR, 0.0)
        excess = diff - slack
        rel = np.where(np.isfinite(tested), np.maximum(excess, 0.0) / ref, np.inf)
        raw = float(np.max(np.where(np.isfinite(tested), diff / ref, np.inf), initial=0.0))
    worst = float(np.max(rel, initial=0.0))
    ok = worst <= PDF_RELATIVE_TOLERANCE
    needed_slack = int(np.count_nonzero((diff > PDF_RELATIVE_TOLERANCE * ref)
                                        & (rel <= PDF_RELATIVE_TOLERANCE)))
    summary = f"max rel. diff {raw:.2g}"
    if needed_slack:
        summary += f" ({needed_slack} pts within ref. rounding)"
    detail = {"points": len(points), "tolerance": PDF_RELATIVE_TOLERANCE, "max_relative_difference": raw,
              "points_within_reference_rounding": needed_slack}
    if not ok:
        k = int(np.argmax(rel))
        detail["worst_point"] = points[k].tolist()
        detail["worst_values"] = [float(tested[k]), float(ref[k])]
        summary += f", at ({', '.join(f'{x:.4g}' for x in points[k])}): {tested[k]:.4g} where {reference} is {ref[k]:.4g}"
        constant = _constant_factor(tested, ref, slack)
        if constant is not None:
            factor, agree, probes = constant
            detail["ratio"] = factor
            where = "" if agree == probes else f" at {agree} of {probes} points"
            phrase = factor_phrase(factor, PDF_RELATIVE_TOLERANCE)
            if phrase:
                detail["factor"] = name_factor(factor, PDF_RELATIVE_TOLERANCE)
                summary = f"pdf = {detail['factor']} x {reference}{where}: {phrase}; {summary}"
            else:
                summary = f"pdf = {factor:.4g} x {reference}{where}; {summary}"
    return CheckResult(ok, worst, summary, details=detail)
