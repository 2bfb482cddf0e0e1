"""The warp conformance checks accept correct warps and reject known-wrong ones."""
import numpy as np
import pytest

from harness.warps.suite import SUITE, run_matrix, select
from harness.warps.evaluate import check_warp
from tests.helpers.wrong_warps import (WRONG, beckmann_pdf, beckmann_sample, cosine_pdf, cosine_sample, disk_pdf, disk_sample,
                                       tent_pdf)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_every_correct_warp_passes_every_check(mcval, mitsuba, seed):
    # The throughput does not depend on the seed: timed at the first only.
    results, level = run_matrix(mcval, mitsuba, list(SUITE), seed=seed, timed=seed == 0)
    assert all(r.checks["throughput"].skipped == (seed != 0) for r in results)
    failures = {r.label: {k: c.summary for k, c in r.checks.items() if c.passed is False}
                for r in results if not r.passed}
    assert not failures
    assert 0 < level < 0.01


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(WRONG))
def test_known_wrong_warp_fails(name):
    sample, pdf, domain, caught_by = WRONG[name]
    result = check_warp(sample, pdf, domain, seed=0, name=name)
    assert not result.passed
    assert result.checks[caught_by].passed is False, {k: c.summary for k, c in result.checks.items()}


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
@pytest.mark.parametrize("sample, pdf, domain, name", [
    (disk_sample, disk_pdf, "disk", "uniform_disk"),
    (cosine_sample, cosine_pdf, "hemisphere", "cosine_hemisphere"),
    (beckmann_sample(0.01), beckmann_pdf(0.01), "hemisphere", "beckmann:0.01"),
    (beckmann_sample(0.3), beckmann_pdf(0.3), "hemisphere", "beckmann:0.3"),
], ids=["disk", "cosine", "beckmann0.01", "beckmann0.3"])
def test_correct_user_warps_pass(sample, pdf, domain, name, seed):
    # Named by their names: judged against the closed forms too (at the full budget).
    result = check_warp(sample, pdf, domain, seed=seed, name=name)
    assert result.passed, {k: c.summary for k, c in result.checks.items()}
    assert result.checks["pdf_vs_mitsuba"].skipped
    assert result.checks["samples_vs_target"].verdict == result.checks["pdf_vs_target"].verdict == "PASS"


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


def test_our_warps_disagreeing_with_mitsuba_are_caught(mcval, mitsuba):
    # Mitsuba's cosine sampler against the uniform-hemisphere distribution: the homogeneity test must fail.
    uniform = mcval.warp("square_to_uniform_hemisphere")
    cosine_ref = mitsuba.warp("square_to_cosine_hemisphere")
    r = check_warp(uniform.sample, uniform.pdf, "hemisphere", reference=cosine_ref)
    assert r.checks["samples_vs_mitsuba"].passed is False
    assert r.checks["pdf_vs_mitsuba"].passed is False


def test_select_rejects_unknown_warps():
    assert [s.key for s in select(["tent", "beckmann:0.1"])] == ["tent", "beckmann:0.1"]
    assert len(select(["beckmann"])) == 5
    with pytest.raises(ValueError, match="unknown warp"):
        select(["tentacle"])


# --- PASS, WARN, FAIL: the boundary of the support and u = 1 -------------------------------------------------

def _tent_inverse(x):
    return np.where(x < 0.5, np.sqrt(2 * x) - 1, 1 - np.sqrt(2 - 2 * x))


def tent_corner_sample(u):
    """The tent by inversion: u = 0 is the corner (-1, -1), where the pdf is 0."""
    return np.stack([_tent_inverse(u[:, 0]), _tent_inverse(u[:, 1])], axis=-1)


def concentric_cosine_sample(u):
    """Shirley-Chiu concentric disk lifted to the hemisphere: u = (0, 0) lands on the horizon."""
    a, b = 2 * u[:, 0] - 1, 2 * u[:, 1] - 1
    first = np.abs(a) > np.abs(b)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(first, a, b)
        phi = np.where(first, np.pi / 4 * b / a, np.pi / 2 - np.pi / 4 * a / b)
    phi = np.where(r == 0, 0.0, phi)
    x, y = r * np.cos(phi), r * np.sin(phi)
    return np.stack([x, y, np.sqrt(np.clip(1 - x * x - y * y, 0, None))], axis=-1)


@pytest.mark.parametrize("sample, pdf, domain", [
    (tent_corner_sample, tent_pdf, "tent"),
    (concentric_cosine_sample, cosine_pdf, "hemisphere"),
], ids=["tent-corner", "concentric-cosine"])
def test_pdf_zero_on_the_boundary_is_a_warning(sample, pdf, domain):
    result = check_warp(sample, pdf, domain, samples=200_000)
    assert result.passed and result.verdict == "WARN" and result.warnings == 1
    hard = result.checks["hard_inputs"]
    assert hard.passed and hard.verdict == "WARN"
    assert [f.kind.key for f in hard.findings] == ["zero_pdf_boundary"]
    assert hard.findings[0].examples[0].startswith("u=(0.0, 0.0)")
    assert "f/pdf at this sample is 0/0: guard it" in hard.findings[0].text()
    assert result.to_json()["verdict"] == "WARN" and result.to_json()["pass"] is True


def test_failure_at_u_one_is_a_warning():
    # log(1 - u) in float64 breaks only at u = 1 itself, which a sampler fed [0, 1) never sees.
    def sample(u):
        with np.errstate(divide="ignore", invalid="ignore"):
            tan2 = -0.09 * np.log(1 - u[:, 1])
            cos = 1 / np.sqrt(1 + tan2)
            sin = np.sqrt(tan2) * cos
        phi = 2 * np.pi * u[:, 0]
        return np.stack([sin * np.cos(phi), sin * np.sin(phi), cos], axis=-1)
    result = check_warp(sample, beckmann_pdf(0.3), "hemisphere", samples=200_000)
    hard = result.checks["hard_inputs"]
    assert result.passed and hard.verdict == "WARN" and hard.figure == 0
    assert [f.kind.key for f in hard.findings] == ["at_u_one"]
    assert "u = 1 is outside [0, 1): fine for samplers fed [0,1)" in hard.findings[0].text()
    assert "[NaN/Inf sample]" in hard.findings[0].examples[0]


def test_failures_come_before_warnings_and_nan_first():
    # NaN at u = (0.5, 0.5); a pdf of 0 on the line x = 0 (u0 = 0.5), inside the support but at its ends.
    def sample(u):
        p = tent_corner_sample(u)
        p[np.all(u == 0.5, axis=1)] = np.nan
        return p

    def pdf(p):
        return np.where(p[:, 0] == 0.0, 0.0, tent_pdf(p))
    hard = check_warp(sample, pdf, "tent", samples=20_000).checks["hard_inputs"]
    assert hard.verdict == "FAIL"
    assert [f.kind.key for f in hard.findings] == ["nan_sample", "zero_pdf_inside", "zero_pdf_boundary"]
    assert [f.severity for f in hard.findings] == ["FAIL", "FAIL", "WARN"]
    assert hard.findings[1].examples == ["u=(0.5, 0.9999999403953552) → sample (0, 0.999655), pdf 0"]
    assert hard.findings[0].examples[0].startswith("u=(0.5, 0.5)")
    assert hard.summary.startswith("NaN/Inf sample ×1: u=(0.5, 0.5)")


def test_domain_check_sorts_zero_pdf_by_where_the_sample_is():
    from harness.warps.domains import get_domain
    from harness.warps.checks import domain_check
    tent = get_domain("tent")
    rng = np.random.default_rng(0)
    edge = domain_check(tent, np.array([[0.2, 0.3], [-1.0, 0.4], [0.5, 1.0]]), tent_pdf, rng)
    assert edge.verdict == "WARN" and edge.details["zero_pdf_on_boundary"] == 2
    inside = domain_check(tent, np.array([[0.2, 0.3]]), lambda p: np.zeros(len(p)), rng)
    assert inside.verdict == "FAIL" and inside.findings[0].kind.key == "zero_pdf_inside"


def test_domains_know_their_boundary():
    from harness.warps.domains import get_domain
    from harness.statistics.constants import BOUNDARY_TOLERANCE as tol
    assert list(get_domain("square").on_boundary(np.array([[0.0, 0.5], [0.5, 1 - 1e-7], [0.5, 0.5]]), tol)) == [
        True, True, False]
    assert list(get_domain("tent").on_boundary(np.array([[-1.0, 0.0], [0.3, 0.999], [0.0, 0.0]]), tol)) == [
        True, False, False]
    assert list(get_domain("disk").on_boundary(np.array([[0.6, 0.8], [0.0, 1 - 1e-7], [0.5, 0.5]]), tol)) == [
        True, True, False]
    assert list(get_domain("hemisphere").on_boundary(np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), tol)) == [
        True, False]
    assert not get_domain("sphere").on_boundary(np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0]]), tol).any()


# --- What users pass: constant and float32 pdfs, extra arguments, wrong shapes ------------------------------

def sphere_sample(u):
    z, phi = 1 - 2 * u[:, 0], 2 * np.pi * u[:, 1]
    r = np.sqrt(np.clip(1 - z * z, 0, None))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


@pytest.mark.parametrize("constant", [1 / (4 * np.pi), np.array([1 / (4 * np.pi)]), np.float32(1 / (4 * np.pi))],
                         ids=["float", "length-1", "float32"])
def test_constant_pdf_is_broadcast(constant):
    result = check_warp(sphere_sample, lambda v: constant, "sphere", samples=200_000)
    assert result.passed, {k: c.summary for k, c in result.checks.items()}


def test_float32_warp():
    result = check_warp(lambda u: disk_sample(u).astype(np.float32),
                        lambda p: disk_pdf(p).astype(np.float32), "disk", samples=200_000)
    assert result.passed, {k: c.summary for k, c in result.checks.items()}


def test_extra_arguments_reach_both_functions():
    def sample(u, alpha):
        return beckmann_sample(alpha)(u)

    def pdf(v, alpha):
        return beckmann_pdf(alpha)(v)
    result = check_warp(sample, pdf, "hemisphere", args=(0.3,), samples=200_000)
    assert result.passed and result.params == [0.3]


@pytest.mark.parametrize("sample, pdf, message", [
    (lambda u: disk_sample(u).T, disk_pdf, r"sample function .*<lambda> returned shape \(2, \d+\) .*expected"),
    (disk_sample, lambda p: disk_pdf(p)[:, None], r"pdf function .*<lambda> returned shape \(\d+, 1\) .*expected"),
    (disk_sample, lambda p: disk_pdf(p)[:10], r"pdf function .* returned shape \(10,\) for \d+ points"),
], ids=["sample-transposed", "pdf-column", "pdf-short"])
def test_wrong_shapes_are_clear_errors(sample, pdf, message):
    with pytest.raises(ValueError, match=message):
        check_warp(sample, pdf, "disk", samples=1000)


# --- WARN in the reports -------------------------------------------------------------------------------------

def test_reports_show_warnings_apart():
    from rich.console import Console

    from harness.report.junit import junit_xml
    from harness.report.warp_html import warp_report_html
    from harness.report.warp_table import warp_table
    from harness.report.warp_outputs import warp_payload
    results = [check_warp(tent_corner_sample, tent_pdf, "tent", samples=20_000, name="tent corner"),
               check_warp(disk_sample, disk_pdf, "disk", samples=20_000, name="disk")]
    console = Console(record=True, width=200)
    console.print(warp_table(results, 0.01))
    text = console.export_text()
    assert "PASS (1 warning)" in text and "FAIL" not in text.replace("red fail", "")
    page = warp_report_html(results, 0.01, {}, {r.label: "cmd" for r in results}, {})
    assert 'class="warn"' in page and "PASS (1 warning)" in page and "0/0: guard it" in page
    payload = warp_payload(results, 0.01, {})
    assert payload["pass"] is True and payload["verdict"] == "WARN"
    assert [w["verdict"] for w in payload["warps"]] == ["WARN", "PASS"]
    assert payload["warps"][0]["checks"]["hard_inputs"]["verdict"] == "WARN"
    xml = junit_xml([], payload["warps"])
    assert 'failures="0"' in xml and "<system-out>hard_inputs: WARN pdf 0" in xml and "<failure" not in xml


def test_the_same_pdf_gets_its_cells_again_and_another_pdf_its_own(monkeypatch):
    from harness.warps import checks as wc
    from harness.warps.domains import get_domain
    searched = []
    real = wc.equal_probability_bins
    monkeypatch.setattr(wc, "equal_probability_bins", lambda *a: searched.append(1) or real(*a))
    disk = get_domain("disk")
    first = wc.equal_probability_cells(disk, disk_pdf, 1000, 0.0)
    again = wc.equal_probability_cells(disk, lambda p: disk_pdf(p).copy(), 1000, 0.0)  # another function, same pdf
    assert len(searched) == 1 and again[0] is first[0]
    # Another pdf, samples or rounding: a search of its own. The integrals are always the pdf's own.
    half = wc.equal_probability_cells(disk, lambda p: 0.5 * disk_pdf(p), 1000, 0.0)
    wc.equal_probability_cells(disk, disk_pdf, 2000, 0.0)
    wc.equal_probability_cells(disk, disk_pdf, 1000, 2.0 ** -23)
    assert len(searched) == 4 and half[1].values.sum() == pytest.approx(0.5, rel=1e-6)
