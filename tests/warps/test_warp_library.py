"""A user's C++ warp library through the C ABI of include/mcval_warps.h (examples/warps/, built by CMake):
the correct build passes at several seeds with the checks against Mitsuba, the course report's pdfs fail,
a sampler broken only at u = 1.0f warns, and a library missing a pdf is one line, with the rest checked."""
import json
from pathlib import Path

import numpy as np
import pytest

from harness.cli import main
from harness.engines.warp_library import WarpLibraryEngine, WarpUnavailable
from harness.warps import check_warp
from harness.warps.suite import SUITE, run_matrix, select
from tests.helpers.warp_libraries import build_warp_library

BUILT = Path(__file__).resolve().parents[2] / "build" / "examples" / "warps"
SAMPLES = 200_000


def _library(variant: str = "") -> WarpLibraryEngine:
    path = BUILT / f"libexample_warps{variant}.so"
    if not path.exists():
        pytest.fail(f"{path} is not built: run `make build`")
    return WarpLibraryEngine(path)


def _verdicts(results) -> dict[str, str]:
    return {r.label: r.verdict for r in results}


@pytest.fixture(scope="module")
def power_cache(tmp_path_factory) -> Path:
    """The power figures of these runs, kept for the next seed's (the same cells give the same figures)."""
    return tmp_path_factory.mktemp("power") / "warp_power.json"


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_correct_library_passes_every_warp_against_mitsuba(mitsuba, seed, power_cache):
    # The throughput does not depend on the seed: timed at the first only.
    results, _ = run_matrix(_library(), mitsuba, list(SUITE), seed=seed, samples=SAMPLES, power_cache=power_cache,
                            timed=seed == 0)
    assert all(r.passed for r in results), _verdicts(results)
    checked = {name for r in results for name, c in r.checks.items() if not c.skipped}
    assert {"pdf_vs_mitsuba", "samples_vs_mitsuba"} <= checked
    throughput = results[0].checks["throughput"]
    if seed == 0:
        assert throughput.details["floor"] is None and "not judged" in throughput.summary
    else:
        assert throughput.skipped


def test_the_course_reports_pdfs_fail_their_normalisation(mitsuba):
    specs = select(["tent", "uniform_disk", "uniform_sphere", "uniform_hemisphere", "cosine_hemisphere"])
    results, _ = run_matrix(_library("_seed"), mitsuba, specs, samples=SAMPLES, power_cache=None, timed=False)
    by_name = {r.warp: r for r in results}
    assert by_name.pop("square_to_tent").passed  # the report's tent is not among its wrong formulas
    for r in by_name.values():
        assert not r.checks["normalisation"].passed and r.checks["normalisation"].figure == pytest.approx(np.pi**2, 1e-4)
        assert not r.checks["pdf_vs_mitsuba"].passed
        assert r.checks["pdf_vs_target"].details["factor"] == "pi^2"  # the samplers are right: only the pdfs fail
        assert r.checks["samples_vs_target"].passed and r.checks["samples_vs_mitsuba"].passed


def test_a_sampler_broken_only_at_u_one_warns(mitsuba):
    (result,), _ = run_matrix(_library("_u_one"), mitsuba, select(["cosine_hemisphere"]), samples=SAMPLES,
                              power_cache=None, timed=False)
    assert result.passed and result.verdict == "WARN"
    hard = result.checks["hard_inputs"]
    assert hard.verdict == "WARN" and hard.details["failures_at_u_one"] > 0 and hard.figure == 0


def test_check_warp_judges_a_float32_warp_on_the_input_it_sees():
    def cosine(u):  # NaN at u1 = 1.0f exactly, as a float32 warp that forgot to clamp
        u = u.astype(np.float32)
        z = np.sqrt(1 - u[:, 1])
        r = np.where(u[:, 1] == 1, np.nan, np.sqrt(u[:, 1]))
        phi = 2 * np.pi * u[:, 0]
        return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)

    def pdf(v):
        return np.where(v[:, 2] > 0, v[:, 2] / np.pi, 0.0)

    as_float64 = check_warp(cosine, pdf, "hemisphere", samples=100_000)
    as_float32 = check_warp(cosine, pdf, "hemisphere", samples=100_000, input_dtype=np.float32)
    assert as_float64.checks["hard_inputs"].verdict == "FAIL"  # u = 1 - 2^-53 is inside [0, 1) in float64
    assert as_float32.checks["hard_inputs"].verdict == "WARN" and as_float32.passed


def test_a_library_missing_a_pdf_is_one_line_and_the_rest_is_checked(tmp_path, capsys):
    source = tmp_path / "partial.c"
    source.write_text('#include "mcval_warps.h"\n'
                      "void square_to_uniform_square(const float *u, float *out, size_t n)"
                      " { for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i]; }\n"
                      "void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n)"
                      " { for (size_t i = 0; i < n; ++i) pdf[i] = (p[2*i] >= 0 && p[2*i] <= 1 && p[2*i+1] >= 0"
                      " && p[2*i+1] <= 1) ? 1.0f : 0.0f; }\n"
                      "void square_to_tent(const float *u, float *out, size_t n) { (void)u; (void)out; (void)n; }\n")
    library = build_warp_library(source, tmp_path)
    with pytest.raises(WarpUnavailable, match="exports square_to_tent but not square_to_tent_pdf"):
        WarpLibraryEngine(library).warp("square_to_tent")
    code = main(["warps", "--warp-library", str(library), "--no-mitsuba", "--samples", "50000",
                 "--out", str(tmp_path / "results")])
    printed = capsys.readouterr().out
    assert code == 1
    assert "FAIL libpartial.so exports square_to_tent but not square_to_tent_pdf" in " ".join(printed.split())
    assert "1 of 1 warps pass" in printed


def test_a_file_that_is_not_a_library_is_refused(tmp_path):
    bad = tmp_path / "libnot.so"
    bad.write_text("not a library")
    with pytest.raises(ValueError, match="cannot load it as a shared library"):
        WarpLibraryEngine(bad)


@pytest.mark.parametrize("exports", ["nothing", "a warp not asked for"])
def test_a_run_that_judges_no_warp_exits_3_and_says_why(tmp_path, capsys, exports):
    source = tmp_path / "lonely.c"
    source.write_text('#include "mcval_warps.h"\nint lonely_unrelated(void) { return 0; }\n' if exports == "nothing" else
                      '#include "mcval_warps.h"\n'
                      "void square_to_uniform_square(const float *u, float *out, size_t n)"
                      " { for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i]; }\n"
                      "void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n)"
                      " { (void)p; for (size_t i = 0; i < n; ++i) pdf[i] = 1.0f; }\n")
    library = build_warp_library(source, tmp_path)
    code = main(["warps", "--warp-library", str(library), "--no-mitsuba", "--only", "tent", "--out",
                 str(tmp_path / "results")])
    printed = " ".join(capsys.readouterr().out.split())
    assert code == 3  # nothing judged (harness/verdict.py)
    assert "No warp judged: lonely exports none of the warps asked for (square_to_tent)" in printed
    assert "— FAIL (nothing was judged)" in printed
    results = json.loads((tmp_path / "results" / "latest" / "results.json").read_text())
    assert results["pass"] is False and results["warps"] == []
    assert results["verdict_reason"] == ("nothing was judged: warps: lonely exports none of the warps asked for "
                                         "(square_to_tent)")
