"""All the checks of one BSDF at one incident direction (harness/bsdfs/checks.py), decided at a given level."""
from __future__ import annotations

import numpy as np

from harness.engines.base import BsdfFunctions
from harness.bsdfs.checks import draw, energy_check, reciprocity_check, sampling_checks, weight_check
from harness.warps.check_result import CheckResult

#: The checks, in the order a report lists them.
CHECKS = ("sampling", "normalisation", "weight", "energy", "reciprocity")
#: The statistical ones: each counts once in the run's Sidak split.
STATISTICAL = ("sampling", "energy")
#: Random (wi, wo) pairs of the reciprocity check.
RECIPROCITY_PAIRS = 10_000


def check_bsdf_at(bsdf: BsdfFunctions, wi: np.ndarray, samples: int, seed: int, level: float) -> dict[str, CheckResult]:
    """The checks of `bsdf` at `wi` from `samples` samples (seeded), the statistical ones decided at the per-test
    `level` (the run's family-wise level split over its statistical checks)."""
    d = draw(bsdf, wi, samples, seed)
    sampling, normalisation = sampling_checks(bsdf, d)
    results = {"sampling": sampling, "normalisation": normalisation, "weight": weight_check(bsdf, d),
               "energy": energy_check(d, level), "reciprocity": reciprocity_check(bsdf, RECIPROCITY_PAIRS, seed)}
    for name in STATISTICAL:
        results[name].decide(level)
    return results
