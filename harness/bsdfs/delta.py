"""The checks of a BSDF's delta lobes (a mirror's, a smooth glass's: samples with an infinite pdf, as
include/mcval_bsdfs.h has them), which no density describes:

- delta lobes: each delta sample leaves by the law of reflection (wo the mirror image of wi about the normal) or
  of refraction (in the plane of incidence, on the other side, every refracted sample in one direction and, for
  a BSDF that names its indices of refraction, at Snell's angle);
- reference delta weights: the expected weight each lobe contributes (its weight times how often it is chosen)
  is the reference engine's, by a two-sample z-test per lobe (equal within float32 rounding where neither
  varies)."""
from __future__ import annotations

import numpy as np

from harness.bsdfs.checks import Draw
from harness.statistics.distributions import norm_sf
from harness.warps.check_result import CheckResult

#: Largest distance between a delta sample's direction and the one its law gives (float32 directions).
DIRECTION_TOLERANCE = 1e-4
#: Relative difference allowed between two lobes' expected weights where neither engine's varies.
WEIGHT_TOLERANCE = 1e-4
#: The lobes, by the side of the surface wo leaves to.
LOBES = ("reflection", "refraction")


def lobe(d: Draw, name: str) -> np.ndarray:
    """The delta samples of the lobe `name` (one of LOBES): those leaving on wi's side, or crossing to the other."""
    side = d.wo[:, 2] * d.wi[2]
    return d.delta & ((side > 0) if name == "reflection" else (side <= 0))


def law_check(d: Draw, eta: float | None = None) -> CheckResult:
    """Each delta sample obeys the law of reflection or of refraction (see the module); where the relative index
    `eta` = int / ext is known, refraction obeys Snell's law with it."""
    mirror = np.array([-d.wi[0], -d.wi[1], d.wi[2]])
    reflected, refracted = d.wo[lobe(d, "reflection")], d.wo[lobe(d, "refraction")]
    off_mirror = np.linalg.norm(reflected - mirror, axis=1) > DIRECTION_TOLERANCE
    # Refraction keeps the plane of incidence and turns the tangential part around; one direction for one wi.
    tangent = np.hypot(d.wi[0], d.wi[1])
    across = np.abs(refracted[:, 0] * d.wi[1] - refracted[:, 1] * d.wi[0]) > DIRECTION_TOLERANCE
    turned = (refracted[:, :2] @ d.wi[:2] > DIRECTION_TOLERANCE * tangent) if tangent > 0 else np.zeros(len(refracted), bool)
    spread = np.linalg.norm(refracted - refracted[:1], axis=1) > DIRECTION_TOLERANCE if len(refracted) else across
    snell = np.zeros(len(refracted), bool)
    if eta is not None:  # sin theta_o = sin theta_i * (eta of wi's side / eta of wo's side)
        eta_ti = 1.0 / eta if d.wi[2] > 0 else eta
        snell = np.abs(np.hypot(refracted[:, 0], refracted[:, 1]) - eta_ti * tangent) > DIRECTION_TOLERANCE
    off_refraction = across | turned | spread | snell
    details = {"reflected": len(reflected), "refracted": len(refracted), "not_mirrored": int(off_mirror.sum()),
               "not_refracted": int(off_refraction.sum()), "tolerance": DIRECTION_TOLERANCE}
    if not (off_mirror.any() or off_refraction.any()):
        return CheckResult(True, 0.0, f"{len(reflected)} delta samples reflected as a mirror reflects, "
                           f"{len(refracted)} refracted in the plane of incidence, all in one direction", details=details)
    if off_mirror.any():
        k = int(np.flatnonzero(off_mirror)[0])
        return CheckResult(False, float(off_mirror.sum()), f"{int(off_mirror.sum())} of {len(reflected)} reflected "
                           f"delta samples are not the mirror direction (e.g. {np.round(reflected[k], 5).tolist()} for "
                           f"{np.round(mirror, 5).tolist()})", details=details)
    k = int(np.flatnonzero(off_refraction)[0])
    how = [what for what, bad in (("leave the plane of incidence", across), ("keep wi's side of it", turned),
                                  ("spread over more than one direction", spread),
                                  (f"miss Snell's angle for eta = {eta:g}" if eta else "", snell)) if bad.any()]
    return CheckResult(False, float(off_refraction.sum()), f"{int(off_refraction.sum())} of {len(refracted)} refracted "
                       f"delta samples {', '.join(how)} (e.g. {np.round(refracted[k], 5).tolist()} for wi = "
                       f"{np.round(d.wi, 5).tolist()})", details=details)


def weights_check(ours: Draw, theirs: Draw) -> CheckResult:
    """The expected weight of each delta lobe, here and in the reference's draw from the same wi (see the
    module); the p-value the smaller of the lobes' (Bonferroni over the two)."""
    parts, ps, details = [], [], {}
    for name in LOBES:
        a, b = (np.where(lobe(x, name), x.weight, 0.0) for x in (ours, theirs))
        mean_a, mean_b = float(a.mean()), float(b.mean())
        se = float(np.sqrt(a.var(ddof=1) / len(a) + b.var(ddof=1) / len(b)))
        if se > 0:
            p = float(2 * norm_sf(abs(mean_a - mean_b) / se))
        else:
            p = 1.0 if abs(mean_a - mean_b) <= WEIGHT_TOLERANCE * max(abs(mean_a), abs(mean_b)) else 0.0
        ps.append(min(1.0, 2 * p))
        details[name] = {"here": mean_a, "reference": mean_b, "standard_error": se, "p_value": p}
        if mean_a or mean_b:
            parts.append(f"{name} {mean_a:.5g} here, {mean_b:.5g} there")
    p = min(ps)
    return CheckResult(None, p, ("; ".join(parts) or "no delta lobe in either") + f"; p = {p:.3g}", p_value=p,
                       details=details)
