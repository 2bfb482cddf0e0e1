"""NaN, +Inf, -Inf and negative radiance never pass: compare_batches and compare_summaries fail them
through their own check, on either side, however few or many pixels hold them."""
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from harness.comparison.compare import compare_batches, compare_summaries
from harness.comparison.summary import summarize
from harness.statistics.welch import BatchStats, welch_p_values

SCENES = Path(__file__).resolve().parents[2] / "scenes"
SPHERE = SCENES / "sphere_plane.xml"
PARAMS = {"res": "32"}
K, SPP = 8, 8
H = W = 32

# Any RuntimeWarning (an invalid value in a division, an overflow) is a failure of these tests.
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def render(mcval, integrator: str, seed: int) -> np.ndarray:
    return mcval.render(str(SPHERE), integrator, SPP, K, seed, PARAMS).batches.astype(np.float64)


@pytest.fixture(scope="module")
def simple(mcval):
    """Two independent renders of one scene: the known-good twin."""
    return render(mcval, "simple", 11), render(mcval, "simple", 12)


@pytest.fixture(scope="module")
def normals(mcval):
    return render(mcval, "normals", 11), render(mcval, "normals", 12)


def damage(batches: np.ndarray, value: float, where: str) -> tuple[np.ndarray, int]:
    """A copy with `value` written somewhere, and how many pixels that touches."""
    out = batches.copy()
    if where == "one pixel":
        out[:, 3, 7, 1] = value
        return out, 1
    if where == "half the image":
        out[:, : H // 2] = value
        return out, H * W // 2
    if where == "all of it":
        out[:] = value
        return out, H * W
    out[K // 2] = value  # one batch only, every pixel of it
    return out, H * W


def test_clean_pairs_pass_at_several_seeds(mcval, simple):
    for seed in (21, 23, 25):
        result = compare_batches(render(mcval, "simple", seed), render(mcval, "simple", seed + 1))
        assert result.passed and result.finite.passed, (seed, result.failed_checks)
    result = compare_batches(*simple)
    assert result.passed
    assert result.to_json()["finite"] == {
        "pass": True, "side": None, "nonfinite": 0, "negative": 0, "locations": [],
        "summary": "every pixel finite and non-negative",
        "test": {"nonfinite": 0, "negative": 0, "locations": []},
        "reference": {"nonfinite": 0, "negative": 0, "locations": []}}


@pytest.mark.parametrize("where", ["one pixel", "half the image", "all of it", "a single batch"])
@pytest.mark.parametrize("side", ["test", "reference"])
@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf], ids=["nan", "+inf", "-inf"])
def test_nonfinite_pixels_fail_the_finite_check(simple, value, side, where):
    test, reference = simple
    if side == "test":
        test, n = damage(test, value, where)
    else:
        reference, n = damage(reference, value, where)
    result = compare_batches(test, reference)
    assert not result.passed
    assert result.failed_checks[0] == "finite"
    first = (3, 7) if where == "one pixel" else (0, 0)
    assert result.finite.summary == f"non-finite pixels: {n} in the {side} image, first at {first}"
    finite = result.to_json()["finite"]
    assert finite["pass"] is False and finite["side"] == side
    assert finite["nonfinite"] == n and finite["negative"] == 0
    assert finite["locations"][0] == list(first) and len(finite["locations"]) == min(n, 20)
    # The statistics never read a non-finite pixel as agreement: it is a certain rejection.
    pixel = result.scales[0]
    assert pixel.failures >= n and pixel.min_p == 0.0
    assert pixel.p_map[first] == 0.0
    json.dumps(result.to_json()["finite"])


def test_welch_gives_nan_not_one_for_nonfinite_inputs():
    ones = BatchStats(np.ones(5), np.full(5, 0.01), 8)
    bad = BatchStats(np.array([np.nan, np.inf, 1.0, 1.0, 1.0]), np.array([0.01, 0.01, np.nan, np.inf, 0.01]), 8)
    p, t, _ = welch_p_values(bad, ones)
    assert np.isnan(p[:4]).all() and np.isnan(t[:4]).all()
    assert p[4] == 1.0  # equal means, finite: no evidence of a difference
    p, _, _ = welch_p_values(ones, ones, scale=np.nan)
    assert np.isnan(p).all()


def test_a_negative_pixel_fails_where_images_must_be_non_negative(simple):
    test, reference = simple
    test = test.copy()
    test[2, 10, 20, 0] = -1e-3
    result = compare_batches(test, reference)
    assert not result.passed and result.failed_checks == ["finite"]
    assert result.finite.summary == "negative pixels: 1 in the test image (must be non-negative), first at (10, 20)"
    assert result.to_json()["finite"]["negative"] == 1


def test_negative_values_pass_in_signed_images(normals):
    test, reference = normals
    assert (test < 0).any() and (reference < 0).any()
    assert compare_batches(test, reference, signed=True).passed
    unsigned = compare_batches(test, reference, signed=False)
    assert not unsigned.passed and unsigned.finite.test.negative > 0 and unsigned.finite.reference.negative > 0
    test = test.copy()
    test[0, 1, 2, 0] = np.nan
    result = compare_batches(test, reference, signed=True)
    assert not result.passed and result.finite.summary == "non-finite pixels: 1 in the test image, first at (1, 2)"


@pytest.mark.parametrize("field,scale", [("mean", "pixel"), ("var_of_mean", "pixel"), ("mean", "tile"),
                                         ("var_of_mean", "image")])
def test_a_stored_summary_with_nonfinite_values_fails(simple, field, scale):
    test, reference = (summarize(b) for b in simple)
    stats = getattr(reference, scale)
    getattr(stats, field).flat[0] = np.nan
    result = compare_summaries(test, reference)
    assert not result.passed and "finite" in result.failed_checks
    assert result.finite.side == "reference" and result.finite.reference.nonfinite >= 1
    assert result.finite.summary.startswith("non-finite pixels: 1 in the reference image, first at (0, 0)")


def test_a_negative_variance_in_a_summary_fails(simple):
    test, reference = (summarize(b) for b in simple)
    reference.pixel.var_of_mean[4, 5, 2] = -1.0
    result = compare_summaries(test, reference, signed=True)
    assert not result.passed and result.finite.reference.negative == 1


def test_a_render_with_one_nan_pixel_fails_the_image_run_path(mcval):
    """What image_run does with our batches (summarize, then compare_summaries): one NaN sample value
    in one batch of a real render fails."""
    scene = str(SCENES / "plane_point.xml")
    mine = mcval.render(scene, "simple", SPP, K, 5, PARAMS).batches
    reference = mcval.render(scene, "simple", SPP, K, 6, PARAMS).batches
    assert compare_summaries(summarize(mine), summarize(reference)).passed
    mine = mine.copy()
    mine[3, 16, 9, 0] *= np.nan
    result = compare_summaries(summarize(mine), summarize(reference))
    assert not result.passed and result.failed_checks[0] == "finite"
    assert result.finite.summary == "non-finite pixels: 1 in the test image, first at (16, 9)"
    # A negative value in one batch is seen too, though the pixel's mean stays positive.
    mine = np.nan_to_num(mine)
    mine[2, 20, 4, 1] = -1e-4
    assert mine[:, 20, 4, 1].mean() > 0
    result = compare_summaries(summarize(mine), summarize(reference))
    assert not result.passed and result.finite.test.negative_at == [(20, 4)]


def test_a_nan_render_fails_in_every_output(tmp_path, monkeypatch, capsys):
    """Through the command line: results.json, junit.xml, report.html and the terminal table all say why."""
    import harness.engines.mcval as mcval_module
    from harness.cli import main

    original = mcval_module.McvalEngine.render

    def one_nan(self, *args, **kwargs):
        result = original(self, *args, **kwargs)
        result.batches = result.batches.copy()
        result.batches[1, 5, 9, :] = np.nan
        return result

    monkeypatch.setattr(mcval_module.McvalEngine, "render", one_nan)
    assert main(["images", "--only", "plane_point:normals", "--out", str(tmp_path)]) == 1
    expected = "non-finite pixels: 1 in the test image"
    terminal = " ".join(capsys.readouterr().out.split())
    assert "FAIL 1 NaN/Inf (test)" in terminal and f"{expected}, first at (5, 9)" in terminal
    run = (tmp_path / "latest").resolve()
    entry = json.loads((run / "results.json").read_text())["images"][0]
    assert entry["pass"] is False
    for name in ("mitsuba", "analytic"):
        finite = entry["tests"][name]["finite"]
        assert finite["pass"] is False and finite["nonfinite"] == 1 and finite["locations"] == [[5, 9]]
    failure = ET.parse(run / "junit.xml").getroot().find(".//failure")
    assert expected in failure.get("message")
    assert f"{expected} at (5, 9)" in (run / "report.html").read_text()
    bad = np.load(run / "images" / "plane_point_normals.npz")["mitsuba_bad_pixels"]
    assert bad[5, 9] == 1 and bad.sum() == 1
    # The next run reads this one (NaN stored as "nan") as its baseline without trouble.
    assert main(["images", "--only", "plane_point:normals", "--out", str(tmp_path)]) == 1
    assert json.loads((tmp_path / "latest" / "results.json").read_text())["baseline"] == run.name
