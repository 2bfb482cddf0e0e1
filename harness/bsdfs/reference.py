"""The checks of a BSDF against a reference engine's plugin of the same name (Mitsuba's): its value and pdf at
the same directions, and a two-sample chi-square of the directions each samples from wi."""
from __future__ import annotations

import numpy as np

from harness.bsdfs.checks import Draw
from harness.engines.base import BsdfFunctions
from harness.warps.bins import Bins
from harness.warps.check_result import CheckResult
from harness.warps.checks import histogram, homogeneity_check
from harness.warps.domains import SPHERE

#: Relative difference allowed between the two engines' values (and pdfs): beyond float32 rounding and the
#: approximations engines differ by (Mitsuba's Beckmann masking, within 0.62 %: docs/findings.md), below any
#: missing factor or a roughness squared once too often.
AGREEMENT_TOLERANCE = 1e-2
#: Values below this share of the largest are compared absolutely (float32 noise where a lobe vanishes).
_FLOOR = 1e-4


def _off(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    scale = max(float(np.max(np.abs(a), initial=0.0)), float(np.max(np.abs(b), initial=0.0)), 1e-30)
    return np.abs(a - b) / np.maximum(np.maximum(np.abs(a), np.abs(b)), _FLOOR * scale)


def values_check(bsdf: BsdfFunctions, reference: BsdfFunctions, wi: np.ndarray, directions: int,
                 seed: int) -> CheckResult:
    """value and pdf of both at `directions` random wo over the whole sphere, within AGREEMENT_TOLERANCE."""
    v = np.random.default_rng(seed).normal(size=(directions, 3))
    wo = v / np.linalg.norm(v, axis=1, keepdims=True)
    wis = np.tile(wi, (directions, 1))
    worst = {}
    for kind in ("eval", "pdf"):
        a, b = getattr(bsdf, kind)(wis, wo), getattr(reference, kind)(wis, wo)
        off = _off(a, b)
        off[~(np.isfinite(a) & np.isfinite(b))] = np.inf
        k = int(np.argmax(off))
        worst[kind] = (float(off[k]), float(a[k]), float(b[k]), float(wo[k, 2]))
    largest = max(w[0] for w in worst.values())
    details = {"directions": directions, "tolerance": AGREEMENT_TOLERANCE,
               **{f"{'value' if k == 'eval' else k}_difference": w[0] for k, w in worst.items()}}
    if largest <= AGREEMENT_TOLERANCE:
        return CheckResult(True, largest, f"value and pdf within {largest:.2g} of the reference's", details=details)
    kind, (off, a, b, z) = max(worst.items(), key=lambda kv: kv[1][0])
    name = "value" if kind == "eval" else "pdf"
    return CheckResult(False, largest, f"{name} differs from the reference's by {off:.3g} (e.g. at cos theta_o = "
                       f"{z:.3f}: {a:.4g} here, {b:.4g} there)", details=details)


def samples_check(d: Draw, reference: BsdfFunctions, bins: Bins, seed: int) -> CheckResult:
    """The directions this BSDF sampled (`d`) and as many the reference samples from the same wi, from one
    distribution: a two-sample chi-square in this BSDF's equal-probability cells (`bins`, those of its sampling
    check), failed samples in a cell of their own."""
    n = len(d.wo)
    u = np.random.default_rng(seed).random((n, 3), dtype=np.float32).astype(np.float64)
    wo, weight, pdf = reference.sample(np.tile(d.wi, (n, 1)), u)
    theirs_failed = (pdf == 0) & (weight == 0)
    ours, theirs = d.wo[~d.failed], wo[~theirs_failed]
    counts = [np.append(histogram(SPHERE, points, bins).ravel(), failed.sum())
              for points, failed in ((ours, d.failed), (theirs, theirs_failed))]
    outside = int(np.count_nonzero(~SPHERE.inside(ours)))
    return homogeneity_check(counts[0], counts[1], outside=outside)
