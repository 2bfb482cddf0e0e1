"""The seed document's warps transcribed literally as a C library (seed_literal/seed_warps.c): every wrong warp
FAILs with the check that names its mistake, with and without Mitsuba and through the Python API, and what the
document gets right (the samplers of the sphere, the hemisphere and the cosine hemisphere) passes. Its Beckmann
(NaN for every sample) is a FAIL of its row beside Mitsuba, not a Dr.Jit error that stops the matrix."""
import json
from pathlib import Path

import numpy as np
import pytest

from harness.cli import main
from harness.engines.warp_library import WarpLibraryEngine
from harness.warps.evaluate import check_warp
from harness.warps.suite import SUITE, select
from tests.helpers.warp_libraries import build_warp_library

SOURCE = Path(__file__).parent / "seed_literal" / "seed_warps.c"
SAMPLES = 50_000

_PI2 = "pdf integrates to 9.8696 = pi^2: the pdf is pi^2 too large"
#: Per warp: the checks that must FAIL, each with a piece of its summary that names the cause, and the checks
#: that must PASS (their part of the document is right).
EXPECTED = {
    "square_to_tent": ({"samples_vs_target": " against square_to_tent's (1-|x|)(1-|y|) on [-1,1]^2",
                        "pdf_vs_target": ": 1 where square_to_tent's (1-|x|)(1-|y|) on [-1,1]^2 is "},
                       ("chi2", "normalisation", "domain")),  # a uniform triangle, true to its own pdf
    "square_to_uniform_disk": ({"normalisation": _PI2, "domain": "sample outside the domain ×",
                                "pdf_vs_target": "pdf = pi^2 x square_to_uniform_disk's 1/pi on the unit disk",
                                "samples_vs_target": " samples outside the domain (against "}, ()),
    "square_to_uniform_sphere": ({"normalisation": _PI2, "pdf_vs_target":
                                  "pdf = pi^2 x square_to_uniform_sphere's 1/(4pi) on the sphere: pi^2 too large"},
                                 ("samples_vs_target", "domain", "hard_inputs")),
    "square_to_uniform_hemisphere": ({"normalisation": _PI2, "domain": "pdf > 0 off the domain ×", "pdf_vs_target":
                                      "pdf = pi^2 x square_to_uniform_hemisphere's 1/(2pi) on the hemisphere: pi^2 "
                                      "too large"}, ("samples_vs_target",)),
    "square_to_cosine_hemisphere": ({"normalisation": _PI2, "pdf_vs_target": "pdf = pi^2 x "
                                     "square_to_cosine_hemisphere's cos(theta)/pi on the hemisphere: pi^2 too large"},
                                    ("samples_vs_target", "domain")),
    "square_to_beckmann": ({"domain": "NaN/Inf sample ×", "hard_inputs": "NaN/Inf sample ×",
                            "samples_vs_target": " NaN/Inf samples (against square_to_beckmann's D(m) cos(theta_m)",
                            "chi2": "pdf is not finite somewhere in the domain",
                            "normalisation": "pdf integrates to inf"}, ()),
}
#: With Mitsuba as well: what its checks must say (FAIL pieces, and PASS) for each warp.
AGAINST_MITSUBA = {
    "square_to_tent": ({"samples_vs_mitsuba": "p = ", "pdf_vs_mitsuba": "where the reference pdf is"}, ()),
    "square_to_uniform_disk": ({"pdf_vs_mitsuba": "pdf = pi^2 x the reference pdf"}, ()),
    "square_to_uniform_sphere": ({"pdf_vs_mitsuba": "pdf = pi^2 x the reference pdf: pi^2 too large"},
                                 ("samples_vs_mitsuba",)),
    "square_to_uniform_hemisphere": ({"pdf_vs_mitsuba": "pdf = pi^2 x the reference pdf"}, ("samples_vs_mitsuba",)),
    "square_to_cosine_hemisphere": ({"pdf_vs_mitsuba": "pdf = pi^2 x the reference pdf"}, ("samples_vs_mitsuba",)),
    "square_to_beckmann": ({"samples_vs_mitsuba": "NaN/Inf samples; not judged: an empty histogram"}, ()),
}


@pytest.fixture(scope="module")
def seed_library(tmp_path_factory) -> Path:
    return build_warp_library(SOURCE, tmp_path_factory.mktemp("seed_literal"))


def _assert_named(warp: str, checks: dict, expected: dict = EXPECTED) -> None:
    """checks: name -> {"verdict", "summary"} (results.json's or a CheckResult's)."""
    failing, passing = expected[warp]
    for check, piece in failing.items():
        assert checks[check]["verdict"] == "FAIL" and piece in checks[check]["summary"], (warp, check, checks[check])
    for check in passing:
        assert checks[check]["verdict"] in ("PASS", "WARN"), (warp, check, checks[check])


def _run(seed_library: Path, tmp_path: Path, *options: str) -> dict:
    out = tmp_path / "results"
    code = main(["warps", "--warp-library", str(seed_library), "--samples", str(SAMPLES), "--out", str(out), *options])
    results = json.loads((out / "latest" / "results.json").read_text())
    assert code == 1 and results["pass"] is False
    return {(w["warp"], (w["params"] or {}).get("alpha")): w for w in results["warps"]}


def test_every_wrong_warp_fails_by_name_without_mitsuba(seed_library, tmp_path):
    rows = _run(seed_library, tmp_path, "--no-mitsuba")
    # The document has no uniform square: left out; every other row of the matrix is there, and fails.
    assert set(rows) == {(s.name, s.alpha) for s in SUITE if s.name != "square_to_uniform_square"}
    for (warp, _), row in rows.items():
        assert row["verdict"] == "FAIL" and row["target"].startswith(warp)
        _assert_named(warp, row["checks"])
    assert rows[("square_to_tent", None)]["checks"]["samples_vs_target"]["p_value"] < 1e-12


@pytest.mark.mitsuba
def test_every_wrong_warp_fails_by_name_beside_mitsuba(seed_library, tmp_path):
    # Beckmann at alpha 0.01: every sample NaN, and Mitsuba's pdf 0 on the whole probe grid (it underflows in
    # float32): no Dr.Jit call on an empty array, a FAIL of the row.
    rows = _run(seed_library, tmp_path, "--only", "tent", "uniform_disk", "uniform_sphere", "uniform_hemisphere",
                "cosine_hemisphere", "beckmann:0.01")
    assert len(rows) == 6
    for (warp, _), row in rows.items():
        assert row["verdict"] == "FAIL"
        _assert_named(warp, row["checks"])
        _assert_named(warp, row["checks"], AGAINST_MITSUBA)


def test_every_wrong_warp_fails_by_name_through_the_python_api(seed_library):
    library = WarpLibraryEngine(seed_library)
    for spec in select(["tent", "uniform_disk", "uniform_sphere", "uniform_hemisphere", "cosine_hemisphere",
                        "beckmann:0.3"]):
        f = library.warp(spec.name, spec.alpha)
        result = check_warp(f.sample, f.pdf, spec.domain, params=spec.params, samples=SAMPLES, name=spec.name,
                            input_dtype=np.float32)
        assert result.verdict == "FAIL"
        _assert_named(spec.name, {k: {"verdict": c.verdict, "summary": c.summary} for k, c in result.checks.items()})
