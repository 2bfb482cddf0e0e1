"""The warp conformance checks accept correct warps and reject known-wrong ones."""
import numpy as np
import pytest

from harness.warp_suite import SUITE, run_matrix, select
from harness.warps import check_warp
from wrong_warps import WRONG, beckmann_pdf, beckmann_sample, cosine_pdf, cosine_sample, disk_pdf, disk_sample


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_every_correct_warp_passes_every_check(ours, mitsuba, seed):
    results, level = run_matrix(ours, mitsuba, list(SUITE), seed=seed)
    failures = {r.label: {k: c.summary for k, c in r.checks.items() if c.passed is False}
                for r in results if not r.passed}
    assert not failures
    assert 0 < level < 0.01


@pytest.mark.parametrize("name", sorted(WRONG))
def test_known_wrong_warp_fails(name):
    sample, pdf, domain, caught_by = WRONG[name]
    result = check_warp(sample, pdf, domain, seed=0, name=name)
    assert not result.passed
    assert result.checks[caught_by].passed is False, {k: c.summary for k, c in result.checks.items()}


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
@pytest.mark.parametrize("sample, pdf, domain", [
    (disk_sample, disk_pdf, "disk"),
    (cosine_sample, cosine_pdf, "hemisphere"),
    (beckmann_sample(0.01), beckmann_pdf(0.01), "hemisphere"),
    (beckmann_sample(0.3), beckmann_pdf(0.3), "hemisphere"),
], ids=["disk", "cosine", "beckmann0.01", "beckmann0.3"])
def test_correct_user_warps_pass(sample, pdf, domain, seed):
    result = check_warp(sample, pdf, domain, seed=seed)
    assert result.passed, {k: c.summary for k, c in result.checks.items()}
    assert result.checks["pdf_vs_mitsuba"].skipped


def test_which_checks_catch_the_seed_constants():
    # A pdf off by a constant factor fails normalisation; pairing mismatches fail chi2.
    sample, pdf, domain, _ = WRONG["seed disk pdf pi"]
    r = check_warp(sample, pdf, domain)
    assert r.checks["normalisation"].passed is False
    assert r.checks["normalisation"].figure == pytest.approx(np.pi**2, rel=1e-4)
    sample, pdf, domain, _ = WRONG["cosine sampler, uniform-hemisphere pdf"]
    r = check_warp(sample, pdf, domain)
    assert r.checks["normalisation"].passed and r.checks["chi2"].passed is False


def test_unguarded_log_shows_up_as_nan_count():
    sample, pdf, domain, _ = WRONG["beckmann log(1-u) unguarded"]
    r = check_warp(sample, pdf, domain, samples=10_000)
    assert r.checks["hard_inputs"].passed is False
    assert r.checks["hard_inputs"].figure > 0


def test_domain_violations_are_counted():
    sample, pdf, domain, _ = WRONG["disk sampler overshooting the rim"]
    r = check_warp(sample, pdf, domain, samples=10_000)
    assert r.checks["domain"].details["samples_outside"] > 0
    sample, pdf, domain, _ = WRONG["disk pdf nonzero outside the disk"]
    r = check_warp(sample, pdf, domain, samples=10_000)
    assert r.checks["domain"].details["pdf_nonzero_outside"] > 0


def test_our_warps_disagreeing_with_mitsuba_are_caught(ours, mitsuba):
    # Mitsuba's cosine sampler against the uniform-hemisphere distribution: the homogeneity test must fail.
    uniform = ours.warp("square_to_uniform_hemisphere")
    cosine_ref = mitsuba.warp("square_to_cosine_hemisphere")
    r = check_warp(uniform.sample, uniform.pdf, "hemisphere", reference=cosine_ref)
    assert r.checks["samples_vs_mitsuba"].passed is False
    assert r.checks["pdf_vs_mitsuba"].passed is False


def test_select_rejects_unknown_warps():
    assert [s.key for s in select(["tent", "beckmann:0.1"])] == ["tent", "beckmann:0.1"]
    assert len(select(["beckmann"])) == 5
    with pytest.raises(ValueError, match="unknown warp"):
        select(["tentacle"])
