"""All the checks of one BSDF at one incident direction (harness/bsdfs/checks.py), decided at a given level."""
from __future__ import annotations

import numpy as np

from harness.engines.base import BsdfFunctions
from harness.bsdfs.checks import (CellCounts, Draw, draw, energy_check, reciprocity_check, sampling_checks,
                                  weight_check)
from harness.bsdfs import delta
from harness.bsdfs.hard_inputs import hard_inputs_check
from harness.bsdfs.reference import reference_draw, samples_check, values_check
from harness.statistics.constants import POWER_TARGET
from harness.warps.bins import Bins
from harness.warps.check_result import CheckResult
from harness.warps.checks import MIN_PILOT, histogram
from harness.warps.domains import SPHERE
from harness.warps.power import noncentral_mass_moved

#: The checks, in the order a report lists them.
CHECKS = ("sampling", "normalisation", "weight", "energy", "reciprocity", "hard inputs")
#: Against a reference engine's plugin of the same name, where there is one.
REFERENCE_CHECKS = ("reference values", "reference samples")
#: Where a BSDF draws samples on a delta lobe (harness/bsdfs/delta.py): its own, and against the reference's.
DELTA_CHECKS = ("delta lobes",)
REFERENCE_DELTA_CHECKS = ("reference delta weights",)
#: The statistical ones, of a BSDF alone and against a reference: each counts once in the run's Sidak split,
#: the delta weights' in every row with a reference (whether a BSDF has a delta lobe is known once it is sampled).
OWN_STATISTICAL = ("sampling", "energy")
REFERENCE_STATISTICAL = ("reference samples", "reference delta weights")
STATISTICAL = OWN_STATISTICAL + REFERENCE_STATISTICAL
#: Every check a row may hold, in the order a report lists them.
ALL_CHECKS = CHECKS + DELTA_CHECKS + REFERENCE_CHECKS + REFERENCE_DELTA_CHECKS
#: The pilot draw's stream, apart from the tested draw's (seed) and the reference's (seed + 1).
PILOT_STREAM = 7
#: The pilot draws this share of a row's samples (all of them below MIN_PILOT): a cell's share of it is known to a
#: few percent, which is all the cells need; the test's samples are the row's own.
PILOT_SHARE = 4
#: Random (wi, wo) pairs of the reciprocity check.
RECIPROCITY_PAIRS = 10_000


def with_power(check: CheckResult, probabilities: np.ndarray, samples: int, level: float,
               two_sample: bool = False) -> None:
    """Adds to a chi-square check of `samples` samples in cells of `probabilities` the sampler defect it finds
    POWER_TARGET of the time at `level`: a share of the samples moved from one half of the mass to the other
    (harness/warps/power.py, by the noncentral chi-square); `two_sample`: against as many samples of another."""
    if check.p_value is None or check.hard_failure is not None or check.not_judged is not None:
        return
    moved = noncentral_mass_moved(probabilities, samples, level, two_sample)
    check.details["detects_mass_moved"] = moved
    check.summary += (f" (finds {moved:.2%} of the samples moved between the halves of the mass {POWER_TARGET:.0%} "
                      "of the time)" if moved is not None else " (finds no share of samples moved up to a half "
                      f"{POWER_TARGET:.0%} of the time)")


def sampling_at(bsdf: BsdfFunctions, wi: np.ndarray, samples: int, seed: int,
                level: float) -> tuple[Draw, CheckResult, CheckResult, Bins, CellCounts | None, np.ndarray | None]:
    """A row's draw and its sampling and normalisation checks (checks.sampling_checks), the sampling check with
    its power at `level`; then its cells, their counts and their probabilities (the failed samples' cell last)."""
    d = draw(bsdf, wi, samples, seed)
    # The cells from a pilot drawn apart (a stream of its own), not from a search of the pdf's marginals.
    pilot = draw(bsdf, wi, max(samples // PILOT_SHARE, min(samples, MIN_PILOT)), [seed, PILOT_STREAM])
    sampling, normalisation, bins, counts = sampling_checks(bsdf, d, pilot)
    probabilities = None
    if counts is not None:
        cells = counts.expected.ravel() / samples
        probabilities = np.append(cells, max(1.0 - cells.sum(), 0.0))
        with_power(sampling, probabilities, samples, level)
    return d, sampling, normalisation, bins, counts, probabilities


def check_bsdf_at(bsdf: BsdfFunctions, wi: np.ndarray, samples: int, seed: int, level: float,
                  reference: BsdfFunctions | None = None, extremes: tuple[BsdfFunctions, ...] = (),
                  histograms: dict | None = None) -> dict[str, CheckResult]:
    """The checks of `bsdf` at `wi` from `samples` samples (seeded), and against `reference` (the same plugin in
    another engine) where given; the statistical ones decided at the per-test `level` (the run's family-wise
    level split over its statistical checks). `extremes`: the same BSDF at the ends of its roughness range, for
    the hard-inputs check (harness/bsdfs/hard_inputs.py). `histograms`, where given, gets the sampling check's
    cell counts, "observed" and "expected", and the reference's, "reference" (for the page's heat maps)."""
    d, sampling, normalisation, bins, counts, probabilities = sampling_at(bsdf, wi, samples, seed, level)
    eta = bsdf.params["int_ior"] / bsdf.params.get("ext_ior", 1.0) if "int_ior" in bsdf.params else None
    if histograms is not None and counts is not None:
        histograms.update(observed=counts.observed, expected=counts.expected)
    results = {"sampling": sampling, "normalisation": normalisation, "weight": weight_check(bsdf, d),
               "energy": energy_check(d, level, eta), "reciprocity": reciprocity_check(bsdf, RECIPROCITY_PAIRS, seed),
               "hard inputs": hard_inputs_check(bsdf, wi, extremes)}
    if d.delta.any():
        results["delta lobes"] = delta.law_check(d, eta)
    if reference is not None:
        theirs = reference_draw(d, reference, seed + 1)
        results["reference values"] = values_check(bsdf, reference, wi, RECIPROCITY_PAIRS, seed)
        their_cells = histogram(SPHERE, theirs.wo[theirs.smooth], bins)  # counted once: the check's and the page's
        results["reference samples"] = samples_check(d, theirs, bins, None if counts is None else counts.observed,
                                                     their_cells)
        if probabilities is not None:  # the power in the sampling check's cells (the delta lobes' left out)
            with_power(results["reference samples"], probabilities, samples, level, two_sample=True)
        if histograms is not None and counts is not None:
            histograms["reference"] = their_cells
        if d.delta.any() or theirs.delta.any():
            results["reference delta weights"] = delta.weights_check(d, theirs)
    for name in STATISTICAL:
        if name in results:
            results[name].decide(level)
    return results
