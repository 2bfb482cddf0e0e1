"""A user's warp library in a process of its own (harness/engines/warp_library.py): a segfault, an abort(), a
write past the output, an exit(0) and a loop that ignores SIGTERM each fail their own warp, naming the library,
the warp and the signal or status, while a correct warp of the same library (which prints on stdout) passes;
a constructor that crashes at load fails every warp asked for. The run writes its results, pages and a
junit.xml that parses, and exits 1."""
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from harness.cli import main
from harness.engines.python_child import ChildFailed
from harness.engines.warp_library import TIMEOUT_ENV, WarpLibraryEngine, call_timeout
from tests.helpers.warp_libraries import build_warp_library

SOURCES = Path(__file__).parent / "warp_libraries"
#: What each warp of misbehaving.c does, as its verdict's line says it.
FAILURES = {
    "square_to_tent": "libmisbehaving.so: square_to_tent was killed by SIGSEGV",
    "square_to_uniform_disk": "libmisbehaving.so: square_to_uniform_disk was killed by SIGABRT",
    "square_to_uniform_sphere": ("libmisbehaving.so: square_to_uniform_sphere wrote past the end of its output "
                                 "(20000 points, 3 floats each)"),
    "square_to_uniform_hemisphere": "libmisbehaving.so: square_to_uniform_hemisphere exited with status 0",
    "square_to_cosine_hemisphere": "libmisbehaving.so: square_to_cosine_hemisphere timed out after 1 s and was killed",
}


@pytest.fixture(scope="module")
def misbehaving(tmp_path_factory) -> Path:
    return build_warp_library(SOURCES / "misbehaving.c", tmp_path_factory.mktemp("misbehaving"))


def _run(library: Path, out: Path, *extra: str) -> tuple[int, dict, ET.ElementTree]:
    code = main(["warps", "--warp-library", str(library), "--no-mitsuba", "--samples", "20000", "--out", str(out),
                 *extra])
    run = out / "latest"
    assert (run / "warps.html").is_file() and (run / "report.html").is_file()
    return code, json.loads((run / "results.json").read_text()), ET.parse(run / "junit.xml")


def test_each_misbehaving_warp_costs_its_own_row(misbehaving, tmp_path, monkeypatch, capsys):
    monkeypatch.setenv(TIMEOUT_ENV, "1")
    code, results, junit = _run(misbehaving, tmp_path)
    printed = " ".join(capsys.readouterr().out.split())
    assert code == 1
    verdicts = {w["warp"]: (w["verdict"], w.get("failure")) for w in results["warps"]}
    assert verdicts == {"square_to_uniform_square": ("PASS", None),
                        **{name: ("FAIL", line) for name, line in FAILURES.items()}}
    for line in FAILURES.values():
        assert f"FAIL {line}" in printed
    cases = {c.get("name"): c.find("failure") for c in junit.iter("testcase")}
    assert cases.pop("square_to_uniform_square") is None
    assert {name: failure.get("message") for name, failure in cases.items()} == FAILURES


def test_a_crashing_constructor_fails_every_warp_asked_for(tmp_path, capsys):
    library = build_warp_library(SOURCES / "constructor_crash.c", tmp_path)
    engine = WarpLibraryEngine(library)
    assert engine.load_failure.reason == "libconstructor_crash.so: loading it was killed by SIGSEGV"
    assert "not loaded: libconstructor_crash.so: loading it was killed by SIGSEGV" in engine.version()
    code, results, junit = _run(library, tmp_path / "out", "--only", "uniform_square", "tent")
    assert code == 1 and results["verdict"] == "FAIL"
    assert [(w["warp"], w["failure"]) for w in results["warps"]] == [
        (name, f"libconstructor_crash.so: loading it was killed by SIGSEGV: {name} could not be checked")
        for name in ("square_to_uniform_square", "square_to_tent")]
    assert len(list(junit.iter("failure"))) == 2


def test_the_library_process_is_replaced_after_a_crash(misbehaving):
    engine = WarpLibraryEngine(misbehaving)
    with pytest.raises(ChildFailed, match="square_to_tent was killed by SIGSEGV"):
        engine.warp("square_to_tent").sample(np.full((4, 2), 0.5))
    u = np.random.default_rng(0).random((1000, 2))
    assert np.array_equal(engine.warp("square_to_uniform_square").sample(u), u.astype(np.float32))


@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf", "soon"])
def test_a_time_limit_that_is_not_a_positive_number_is_refused(monkeypatch, value):
    monkeypatch.setenv(TIMEOUT_ENV, value)
    with pytest.raises(ValueError, match=f"{TIMEOUT_ENV}='{value}': give a positive number of seconds"):
        call_timeout()


def test_a_pdf_infinite_at_one_point_in_a_hundred_fails_its_warp_and_the_page_renders(tmp_path):
    source = tmp_path / "infinite.c"
    source.write_text('#include <math.h>\n#include "mcval_warps.h"\n'
                      "void square_to_uniform_square(const float *u, float *out, size_t n)"
                      " { for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i]; }\n"
                      "void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n)"
                      " { (void)p; for (size_t i = 0; i < n; ++i) pdf[i] = i % 100 == 0 ? INFINITY : 1.0f; }\n")
    code, results, junit = _run(build_warp_library(source, tmp_path), tmp_path / "out")
    (warp,) = results["warps"]
    assert code == 1 and warp["verdict"] == "FAIL"
    assert warp["checks"]["chi2"]["summary"] == "pdf is not finite somewhere in the domain"
    assert warp["checks"]["normalisation"]["summary"] == "pdf integrates to inf"
    assert "pdf is not finite" in junit.find(".//failure").get("message")


def test_a_warp_that_crashes_only_when_timed_fails_its_row_after_its_checks(tmp_path, capsys):
    # The throughput is timed after the checks (harness/warps/suite.py: time_matrix), on a million samples a call.
    source = tmp_path / "timed_crash.c"
    source.write_text('#include <signal.h>\n#include "mcval_warps.h"\n'
                      "void square_to_uniform_square(const float *u, float *out, size_t n)"
                      " { if (n > 500000) raise(SIGSEGV); for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i]; }\n"
                      "void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n)"
                      " { (void)p; for (size_t i = 0; i < n; ++i) pdf[i] = 1.0f; }\n"
                      "void square_to_tent(const float *u, float *out, size_t n)"
                      " { for (size_t i = 0; i < 2 * n; ++i) { float x = 2 * u[i];"
                      " out[i] = x < 1 ? __builtin_sqrtf(x) - 1 : 1 - __builtin_sqrtf(2 - x); } }\n"
                      "void square_to_tent_pdf(const float *p, float *pdf, size_t n)"
                      " { for (size_t i = 0; i < n; ++i) { float a = 1 - __builtin_fabsf(p[2*i]),"
                      " b = 1 - __builtin_fabsf(p[2*i+1]); pdf[i] = a > 0 && b > 0 ? a * b : 0.0f; } }\n")
    code, results, _ = _run(build_warp_library(source, tmp_path), tmp_path / "out", "--only", "uniform_square", "tent")
    assert code == 1
    square, tent = results["warps"]
    assert (square["verdict"], square["failure"]) == (
        "FAIL", "libtimed_crash.so: square_to_uniform_square was killed by SIGSEGV")
    assert tent["pass"] and tent["checks"]["throughput"]["figure"] > 0  # timed, not skipped
