"""A check that cannot judge does not pass: planted NaN samples, infinite pdfs, empty sample sets and pdfs that
integrate far from one each FAIL, by name or as "not judged", never with a p-value that passes."""
import numpy as np
import pytest

from harness.engines.base import WarpFunctions
from harness.warps import checks as wc
from harness.warps.check_result import CheckResult
from harness.warps.evaluate import check_warp, decide, evaluate_warp
from harness.warps.pdf_agreement import pdf_agreement_check
from tests.helpers.wrong_warps import disk_pdf, disk_sample

SAMPLES = 100_000


def _failed(result) -> dict:
    return {k: c.summary for k, c in result.checks.items() if c.passed is False}


def _nan_samples(u):
    return np.full((len(u), 2), np.nan)


def _reference() -> WarpFunctions:
    """A correct disk as a reference engine gives it (no Mitsuba needed)."""
    return WarpFunctions(disk_sample, disk_pdf, lambda n: (lambda: None))


def test_nan_samples_fail_every_sample_check():
    result = check_warp(_nan_samples, disk_pdf, "disk", samples=SAMPLES, reference=_reference(), name="uniform_disk")
    failed = _failed(result)
    assert failed["chi2"] == f"{SAMPLES} NaN/Inf samples"
    assert failed["domain"].startswith(f"NaN/Inf sample ×{SAMPLES}")
    # An empty histogram (which passed with p = 1): a hard failure that says it could not judge.
    assert failed["samples_vs_mitsuba"] == f"{SAMPLES} NaN/Inf samples; not judged: an empty histogram (0 and {SAMPLES} counts)"
    assert result.checks["samples_vs_mitsuba"].not_judged
    assert failed["samples_vs_target"].startswith(f"{SAMPLES} NaN/Inf samples (against square_to_uniform_disk's")


def test_a_million_nan_samples_beside_mitsuba_are_not_judged(mitsuba):
    # The homogeneity test of an empty histogram against Mitsuba's (it passed with p = 1).
    result = check_warp(_nan_samples, disk_pdf, "disk", samples=1_000_000, name="uniform_disk",
                        reference=mitsuba.warp("square_to_uniform_disk"))
    check = result.checks["samples_vs_mitsuba"]
    assert check.passed is False and check.not_judged == "an empty histogram (0 and 1000000 counts)"
    assert check.summary.startswith("1000000 NaN/Inf samples; not judged")


def test_a_few_nan_samples_fail_the_sample_checks_by_name():
    def sample(u):
        p = disk_sample(u)
        p[:10] = np.inf
        return p
    result = check_warp(sample, disk_pdf, "disk", samples=SAMPLES, reference=_reference(), name="uniform_disk")
    failed = _failed(result)
    assert failed["chi2"] == failed["samples_vs_mitsuba"] == "10 NaN/Inf samples"
    assert failed["samples_vs_target"].startswith("10 NaN/Inf samples")


def test_an_infinite_pdf_fails_chi2_normalisation_and_domain():
    def pdf(p):
        r2 = np.sum(p * p, axis=1)
        return np.where(r2 < 0.01, np.inf, disk_pdf(p))
    failed = _failed(check_warp(disk_sample, pdf, "disk", samples=SAMPLES))
    assert failed["chi2"] == "pdf is not finite somewhere in the domain"
    assert failed["normalisation"] == "pdf integrates to inf"
    assert "NaN/Inf pdf at a sample" in failed["domain"]


@pytest.mark.parametrize("samples, chi2", [
    (0, "not judged: fewer than two cells expect 5 samples or more (0 expected in all, 0 observed)"),
], ids=["no samples"])
def test_an_empty_sample_set_is_not_judged(samples, chi2):
    result = check_warp(disk_sample, disk_pdf, "disk", samples=samples, reference=_reference(), name="uniform_disk")
    failed = _failed(result)
    assert failed["chi2"] == chi2 and failed["samples_vs_target"].startswith("not judged: fewer than two cells")
    assert failed["samples_vs_mitsuba"] == "not judged: an empty histogram (0 and 0 counts)"
    assert not result.passed and result.verdict == "FAIL"


def test_every_sample_outside_the_domain_fails():
    result = check_warp(lambda u: disk_sample(u) + 3.0, disk_pdf, "disk", samples=SAMPLES, reference=_reference())
    failed = _failed(result)
    assert failed["chi2"] == failed["samples_vs_mitsuba"].split(";")[0] == f"{SAMPLES} samples outside the domain"
    assert result.checks["samples_vs_mitsuba"].not_judged.startswith("an empty histogram")


@pytest.mark.parametrize("integral", [1e-5])  # and 6e-6: tests/statistics/test_chi2.py
def test_a_pdf_integrating_far_below_one_fails_and_chi2_does_not_pass(integral):
    # Its expected counts (1e6 * integral in all) pooled into one bin, which passed with p = 1.
    result = check_warp(disk_sample, lambda p: integral * disk_pdf(p), "disk", samples=1_000_000)
    failed = _failed(result)
    assert failed["chi2"].startswith("not judged: fewer than two cells expect 5 samples or more")
    assert failed["normalisation"] == f"pdf integrates to {integral:.5g}"
    assert np.isnan(result.checks["chi2"].p_value) and result.checks["chi2"].to_json()["not_judged"]


def test_a_reference_that_is_0_at_every_probe_is_not_judged():
    check = pdf_agreement_check(disk_sample(np.random.default_rng(0).random((100, 2))), disk_pdf,
                                   lambda p: np.zeros(len(p)), "the reference pdf")
    assert check.passed is False and check.summary == "not judged: the reference pdf is 0 at all 100 probe points"


def test_not_judged_counts_in_the_level_and_fails_whatever_the_level():
    judged = CheckResult(None, 0.5, "p = 0.5", p_value=0.5)
    unjudged = wc.not_judged("no samples")
    result = evaluate_warp(disk_sample, disk_pdf, "disk", samples=1000)
    result.checks.update(extra=judged, other=unjudged)
    decide([result], alpha=1e-12)  # a level that passes any p-value
    assert judged.passed is True and unjudged.passed is False and unjudged.verdict == "FAIL"
    assert unjudged.details["level"] == judged.details["level"]
