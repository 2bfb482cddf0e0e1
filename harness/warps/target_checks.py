"""A warp judged against its name: its samples against the closed form its name promises (harness.warps.targets),
and its pdf against that closed form, with no second engine.

samples_vs_target is Pearson's chi-square of the samples the other checks drew, in equal-probability cells of
the target (exact quantiles of its marginals, as fine as the samples' float32 rounding allows, see
warp_bins.cdf_cells), with the exact probability of each cell; pdf_vs_target compares the pdf
with the closed form at the samples, at the centres of the target's cells and on a uniform grid, within the
tolerance of pdf_vs_mitsuba. A warp of a name mcval does not know skips both, saying it is judged against its
own pdf only.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.warps import checks as wc
from harness.warps.bins import Bins
from harness.warps.check_result import CheckResult, skipped
from harness.warps.domains import Domain
from harness.warps.pdf_agreement import pdf_agreement_check
from harness.warps.targets import Target

#: Our samples among the points where the pdf is compared with the target (and with the reference).
PDF_PROBES = 100_000


@dataclass
class TargetOutcome:
    """The two checks against the target, and the histogram behind the chi-square (None without a target)."""

    checks: dict[str, CheckResult]
    #: Our samples in the target's cells, and the counts the target expects there.
    observed: np.ndarray | None = None
    expected: np.ndarray | None = None
    bins: Bins | None = None


def judged_by_own_pdf(name: str) -> TargetOutcome:
    """Both checks skipped, saying why: mcval knows no closed form for `name`."""
    reason = f"no closed form known for {name!r}: judged against its own pdf only"
    return TargetOutcome({"pdf_vs_target": skipped(reason), "samples_vs_target": skipped(reason)})


def target_checks(dom: Domain, target: Target, pdf: wc.Pdf, inside_points: np.ndarray,
                  param: tuple[np.ndarray, np.ndarray], lost: tuple[int, int], samples: int, quantum: float,
                  histogrammed: tuple[Bins, np.ndarray] | None = None) -> TargetOutcome:
    """pdf_vs_target and samples_vs_target of one warp.

    inside_points: our samples inside the domain, `param` their parameters (dom.to_param); lost: (samples
    outside the domain, of which NaN/Inf), a hard failure as in chi2; samples: how many were drawn; quantum: the
    rounding of the run's samples (warp_bins.sample_quantum, it limits the cells); histogrammed: cells the samples
    are counted in already, with their counts (reused if the target's cells are the same).
    """
    bins, probabilities = target.cells(samples, quantum)
    if histogrammed is not None and bins.same_edges(histogrammed[0]):
        observed = histogrammed[1]
    else:
        observed = wc.histogram(dom, inside_points, bins, param)
    samples_check = wc.chi2_check(observed, probabilities, lost[0], bins, lost[1],
                                 against=f"against {target.label}")
    probes = np.concatenate([inside_points[:PDF_PROBES], wc.parameter_grid(dom, bins.s_edges, bins.t_edges),
                             wc.parameter_grid(dom)])
    pdf_check = pdf_agreement_check(probes, pdf, target.pdf, target.label)
    for check in (samples_check, pdf_check):
        check.details["target"] = target.label
    return TargetOutcome({"pdf_vs_target": pdf_check, "samples_vs_target": samples_check}, observed,
                         probabilities * samples, bins)
