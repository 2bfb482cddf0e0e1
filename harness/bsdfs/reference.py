"""The checks of a BSDF against a reference engine's plugin of the same name (Mitsuba's): its value and pdf at
the same directions, and a two-sample chi-square of the directions each samples from wi."""
from __future__ import annotations

import numpy as np

from harness.bsdfs.checks import Draw, draw
from harness.bsdfs.delta import LOBES, lobe
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
    """value and pdf of both at `directions` random wo over the whole sphere, within AGREEMENT_TOLERANCE; the pdf
    where either value is nonzero (a density where neither scatters light weighs no estimate, and the sampling and
    normalisation checks judge the tested one's there)."""
    v = np.random.default_rng(seed).normal(size=(directions, 3))
    wo = v / np.linalg.norm(v, axis=1, keepdims=True)
    wis = np.tile(wi, (directions, 1))
    values = {kind: (getattr(bsdf, kind)(wis, wo), getattr(reference, kind)(wis, wo)) for kind in ("eval", "pdf")}
    dark = (values["eval"][0] == 0) & (values["eval"][1] == 0)
    worst = {}
    for kind, (a, b) in values.items():
        off = _off(a, b)
        off[~(np.isfinite(a) & np.isfinite(b))] = np.inf
        if kind == "pdf":
            off[dark & np.isfinite(off)] = 0.0
        k = int(np.argmax(off))
        worst[kind] = (float(off[k]), float(a[k]), float(b[k]), float(wo[k, 2]))
    largest = max(w[0] for w in worst.values())
    # A reference whose pdf is not 0 where it scatters nothing (Mitsuba's roughplastic below the surface).
    stray = int(np.count_nonzero(dark & (values["pdf"][1] != 0)))
    details = {"directions": directions, "tolerance": AGREEMENT_TOLERANCE, "reference_pdf_without_value": stray,
               **{f"{'value' if k == 'eval' else k}_difference": w[0] for k, w in worst.items()}}
    if largest <= AGREEMENT_TOLERANCE:
        note = f"; the reference's pdf is not 0 at {stray} where neither scatters light" if stray else ""
        return CheckResult(True, largest, f"value and pdf within {largest:.2g} of the reference's{note}",
                           details=details)
    kind, (off, a, b, z) = max(worst.items(), key=lambda kv: kv[1][0])
    name = "value" if kind == "eval" else "pdf"
    return CheckResult(False, largest, f"{name} differs from the reference's by {off:.3g} (e.g. at cos theta_o = "
                       f"{z:.3f}: {a:.4g} here, {b:.4g} there)", details=details)


def reference_draw(d: Draw, reference: BsdfFunctions, seed: int) -> Draw:
    """As many samples of the reference from d's wi, from uniforms of their own."""
    return draw(reference, d.wi, len(d.wo), seed)


def _counts(d: Draw, bins: Bins, cells: np.ndarray | None = None) -> np.ndarray:
    """The drawn directions per cell (`cells` where the caller has them), then the failed samples, then the delta
    samples of each lobe (delta.LOBES: reflected, refracted)."""
    cells = histogram(SPHERE, d.wo[d.smooth], bins) if cells is None else cells
    return np.concatenate([cells.ravel(), [d.failed.sum(), *(lobe(d, name).sum() for name in LOBES)]])


def samples_check(d: Draw, theirs: Draw, bins: Bins, cells: np.ndarray | None = None,
                  their_cells: np.ndarray | None = None) -> CheckResult:
    """The directions this BSDF sampled (`d`) and those the reference sampled from the same wi (`theirs`), from one
    distribution: a two-sample chi-square in this BSDF's equal-probability cells (`bins`, those of its sampling
    check), failed samples in a cell of their own and each side's delta samples in one. `cells`, `their_cells`:
    each side's smooth samples per cell where the caller has counted them (the sampling check, the page)."""
    outside = int(np.count_nonzero(~SPHERE.inside(d.wo[d.smooth])))
    ours, reference = _counts(d, bins, None if outside else cells), _counts(theirs, bins, their_cells)
    used = np.flatnonzero((ours > 0) | (reference > 0))
    if not outside and len(used) == 1 and used[0] >= len(ours) - 2:  # a mirror's, or a glass's at total reflection
        lobe = "reflected" if used[0] == len(ours) - 2 else "refracted"
        return CheckResult(None, 1.0, f"every sample of both on the {lobe} delta lobe; p = 1", p_value=1.0,
                           details={"cells": int(len(ours)), "delta_samples": int(ours[used[0]])})
    return homogeneity_check(ours, reference, outside=outside)
