"""The hard-inputs check of a BSDF: at the inputs where a sampler or a formula divides by zero or leaves its domain
(wi on the normal, at grazing incidence and below the surface, u at 0 and at 1 - 2^-24, wo on the normal, grazing,
in the tangent plane and below; and, for a BSDF with a roughness `alpha`, alpha at 1e-4 and 1), every value, pdf
and weight is a number and none is negative, a pdf is finite unless the sample is on a delta lobe, and every
direction drawn is a unit vector."""
from __future__ import annotations

import itertools

import numpy as np

from harness.engines.base import BsdfFunctions
from harness.warps.check_result import CheckResult

#: The largest uniform below 1 in float32.
ONE_BELOW = 1.0 - 2.0 ** -24
#: Roughnesses at the ends of the range a microfacet BSDF must take.
ALPHAS = (1e-4, 1.0)
_COS_GRAZING = 1e-6
#: How far from unit length a drawn direction may be (float32 arithmetic).
UNIT_TOLERANCE = 1e-3


def _unit(v) -> np.ndarray:
    v = np.asarray(v, np.float64)
    return v / np.linalg.norm(v)


def hard_directions(wi: np.ndarray) -> np.ndarray:
    """wi itself, on the normal, grazing, and each of them mirrored below the surface (for a BSDF that sees both
    sides; one that does not must still answer with zeros)."""
    s = np.sqrt(1 - _COS_GRAZING ** 2)
    above = [np.asarray(wi, np.float64), np.array([0.0, 0.0, 1.0]), np.array([s, 0.0, _COS_GRAZING])]
    return np.array(above + [v * [1, 1, -1] for v in above])


_U = np.array(list(itertools.product((0.0, 0.5, ONE_BELOW), repeat=3)))
_WO = np.array([[0.0, 0.0, 1.0], _unit([1.0, 0.0, _COS_GRAZING]), [0.0, 1.0, 0.0], [0.0, 0.0, -1.0],
                _unit([0.3, -0.4, 0.5]), _unit([0.3, -0.4, -0.5])])


def _problems(bsdf: BsdfFunctions, wi_all: np.ndarray) -> list[str]:
    """What is wrong at the hard inputs, one phrase each (at most one per kind)."""
    found: dict[str, str] = {}
    wi = np.repeat(wi_all, len(_U), axis=0)
    wo, weight, pdf = bsdf.sample(wi, np.tile(_U, (len(wi_all), 1)))
    at = lambda k: f"wi = {np.round(wi[k], 6).tolist()}, u = {_U[k % len(_U)].tolist()}"  # noqa: E731
    for name, a in (("weight", weight), ("sampled pdf", pdf)):
        bad = np.isnan(a) | (a < 0) | (np.isinf(a) if name == "weight" else False)  # a delta sample's pdf is inf
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            found[name] = f"{int(bad.sum())} {name}s NaN, infinite or negative (e.g. {a[k]:.4g} at {at(k)})"
    drawn = (pdf != 0) | (weight != 0)
    length = np.linalg.norm(wo, axis=1)
    off = drawn & ~(np.abs(length - 1) <= UNIT_TOLERANCE)
    if off.any():
        k = int(np.flatnonzero(off)[0])
        found["wo"] = f"{int(off.sum())} drawn directions not unit vectors (e.g. length {length[k]:.4g} at {at(k)})"
    pairs_wi = np.repeat(wi_all, len(_WO), axis=0)
    pairs_wo = np.tile(_WO, (len(wi_all), 1))
    for kind in ("eval", "pdf"):
        a = getattr(bsdf, kind)(pairs_wi, pairs_wo)
        bad = ~np.isfinite(a) | (a < 0)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            found[kind] = (f"{kind} NaN, infinite or negative at {int(bad.sum())} pairs (e.g. {a[k]:.4g} at wi = "
                           f"{np.round(pairs_wi[k], 6).tolist()}, wo = {np.round(pairs_wo[k], 6).tolist()})")
    return list(found.values())


def hard_inputs_check(bsdf: BsdfFunctions, wi: np.ndarray, extremes: tuple[BsdfFunctions, ...] = ()) -> CheckResult:
    """The check of the module at this row's wi, for `bsdf` and the same BSDF at its `extremes` of roughness."""
    directions = hard_directions(wi)
    problems = [f"{b.label}: {p}" if b is not bsdf else p
                for b in (bsdf, *extremes) for p in _problems(b, directions)]
    details = {"incident_directions": len(directions), "uniforms": len(_U), "directions": len(_WO),
               "variants": [b.label for b in (bsdf, *extremes)]}
    if not problems:
        return CheckResult(True, 0.0, f"numbers, none negative, at {len(directions)} hard wi x {len(_U)} hard u and "
                           f"{len(_WO)} hard wo" + (f", also at {', '.join(b.label for b in extremes)}"
                                                    if extremes else ""), details=details)
    return CheckResult(False, float(len(problems)), "; ".join(problems), details=details)


def roughness_extremes(make, values: dict[str, float]) -> tuple[BsdfFunctions, ...]:
    """The BSDF `make(values)` makes, at each of ALPHAS where it takes an `alpha` (none otherwise)."""
    if "alpha" not in values:
        return ()
    return tuple(make({**values, "alpha": a}) for a in ALPHAS)
