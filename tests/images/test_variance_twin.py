"""The known-wrong twin of the variance test: ambient occlusion sampled uniformly on the hemisphere and weighted
by 2 cos (the test build's ao_uniform, in place of ao) has ao's mean, so every scale of the mean test passes it;
against Mitsuba drawing the cosine-weighted estimator it fails on its variance alone. mcval passes."""
import json

from harness.cli import main
from tests.helpers.render_wrappers import write_wrapper

CASES = ["cornell:ao", "crevice:ao"]


def _cases(out):
    return {c["scene"]: c for c in json.loads((out / "latest" / "results.json").read_text())["images"]}


def test_uniform_hemisphere_ao_fails_on_its_variance_alone(tmp_path, monkeypatch):
    monkeypatch.setenv("MCVAL_RENDER", str(write_wrapper(tmp_path, "ao_uniform", "ao")))
    out = tmp_path / "results"
    assert main(["images", "--only", *CASES, "--out", str(out)]) == 1
    for scene, case in _cases(out).items():
        test = case["tests"]["mitsuba"]
        assert not case["pass"], scene
        assert all(s["pass"] for s in test["tests"]), scene  # every scale of the mean test passes it
        variance = test["variance"]
        assert variance["same_estimator"] and variance["verdict"] == "FAIL" and variance["ratio"] > 1.2, (scene, variance)


def test_our_cosine_weighted_ao_passes_the_variance_test(tmp_path):
    out = tmp_path / "results"
    assert main(["images", "--only", *CASES, "--out", str(out)]) == 0
    for scene, case in _cases(out).items():
        variance = case["tests"]["mitsuba"]["variance"]
        assert variance["verdict"] == "PASS" and abs(variance["ratio"] - 1) < 0.1, (scene, variance)
