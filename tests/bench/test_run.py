"""Speed against error: the error measure, the fits, and the bench command's JSON."""
import json

import numpy as np
import pytest

from harness.bench.ladder import Curve, Step, relmse
from harness.comparison.summary import summarize


def test_relmse_removes_the_reference_noise():
    rng = np.random.default_rng(0)
    mu, sx, sr, k = 0.5, 0.05, 0.05, 16
    reference = summarize(mu + rng.normal(0, sr * np.sqrt(k), (k, 64, 64, 3)))
    image = mu + rng.normal(0, sx, (64, 64, 3))
    from harness.images.references import Reference
    ref = Reference(reference, 0, {}, "synthetic")
    expected = sx**2 / (mu**2 + 1e-2)
    assert relmse(image, ref) == pytest.approx(expected, rel=0.15)
    # Without the correction the reference's own noise would double the error.
    naive = np.mean((image - reference.pixel.mean) ** 2 / (reference.pixel.mean**2 + 1e-2))
    assert naive > 1.5 * expected


def test_fits_efficiency_and_time_to_target():
    steps = [Step(s, [0.01 * s] * 3, [0.5 / s] * 3, [0.1] * 3) for s in (1, 2, 4, 8, 16, 32, 64)]
    curve = Curve("x", "render only", steps, 0.1)
    assert curve.fit("spp")[0] == pytest.approx(-1.0)
    assert curve.fit("seconds")[0] == pytest.approx(-1.0)
    assert curve.efficiency() == pytest.approx(1 / (0.5 * 0.01))
    assert curve.time_to(1e-3) == pytest.approx(0.5 / 1e-3 * 0.01, rel=1e-6)


@pytest.mark.slow
def test_bench_command_writes_speed_entries(tmp_path):
    from harness.cli import main
    assert main(["bench", "--only", "cornell:simple", "--engines", "mcval", "mitsuba", "--max-spp", "8",
                 "--runs", "2", "--seed-runs", "0", "--throughput-runs", "0", "--out", str(tmp_path)]) == 0
    data = json.loads((tmp_path / "bench-latest" / "results.json").read_text())
    (entry,) = data["speed"]
    assert entry["integrator"] == "simple" and entry["scene"] == "cornell"
    assert entry["efficiency_ratio"] > 0
    labels = {"mcval/independent", "mcval/sobol", "mitsuba/independent", "mitsuba/ldsampler", "mitsuba/multijitter"}
    assert set(entry["slope"]) == set(entry["seconds"]) == labels
    same = entry["efficiency_ratio_same_sampler"]
    assert (same["tested"], same["reference"]) == ("mcval/independent", "mitsuba/independent")
    assert same["ratio"] == entry["efficiency_ratio"]
    best = entry["efficiency_ratio_best"]
    assert best["tested"] in labels and best["reference"] in labels and best["ratio"] > 0
    page = (tmp_path / "bench-latest" / "bench.html").read_text()
    assert page.count("<img") == 2 and "best against best" in page and "Sampler convergence" in page
    slopes = data["sampler_slopes"]["slopes"]
    assert set(slopes) == {"simple", "ao"} and all(set(v) == {"independent", "sobol"} for v in slopes.values())


def test_same_sampler_and_best_against_best_pick_their_curves():
    def curve(name, c, s):
        return Curve(name, "render only", [Step(k, [s * k] * 3, [c / k] * 3, [0.1] * 3) for k in (16, 32, 64)], 0.1)
    from harness.bench.run import CaseBench
    bench = CaseBench(None, {"mcval/independent": curve("a", 1.0, 0.01),    # efficiency 100
                             "mcval/sobol": curve("b", 0.25, 0.01),         # 400
                             "mitsuba/independent": curve("c", 1.0, 0.02),  # 50
                             "mitsuba/ldsampler": curve("d", 0.5, 0.01),    # 200
                             "mitsuba/multijitter": curve("e", 1.0, 0.01)}, np.zeros(3),  # 100
                      best={"mcval": ("sobol",), "mitsuba": ("ldsampler", "multijitter")})
    same, best = bench.comparison("independent"), bench.comparison(None)
    assert same.pop("missing") == [] and best.pop("missing") == []
    assert same == pytest.approx({"ratio": 2.0, "tested": "mcval/independent", "reference": "mitsuba/independent",
                                  "tested_sampler": "independent", "reference_sampler": "independent"})
    assert best == pytest.approx({"ratio": 2.0, "tested": "mcval/sobol", "reference": "mitsuba/ldsampler",
                                  "tested_sampler": "sobol", "reference_sampler": "ldsampler"})
    assert bench.efficiency_ratio() == pytest.approx(2.0)
    # Best against best picks among the stratified samplers, even where independent did better.
    bench.curves["mitsuba/independent"] = curve("c", 0.1, 0.01)  # 1000
    assert bench.comparison(None)["reference"] == "mitsuba/ldsampler"


def test_an_engine_without_curves_is_named_not_taken_for_noise():
    from harness.bench.run import CaseBench
    from harness.report.bench_table import bench_table
    from rich.console import Console
    curve = Curve("a", "render only", [Step(k, [0.01 * k] * 3, [1 / k] * 3, [0.1] * 3) for k in (16, 32)], 0.1)
    bench = CaseBench(None, {"mcval/independent": curve}, np.zeros(3), tested="mcval", reference="mitsuba-native")
    assert bench.comparison("independent")["missing"] == ["mitsuba-native"]
    bench.case = type("Case", (), {"scene": "cornell", "integrator": "ao"})()
    console = Console(record=True, width=200)
    console.print(bench_table([bench], []))
    text = console.export_text()
    assert "no mitsuba-native curve" in text and "below ref. noise" not in text
    assert "efficiency tested/mitsuba-native" in text


def test_ratios_compare_the_steps_both_curves_rendered():
    from harness.bench.run import CaseBench
    # Efficiency growing with spp, as a stratified sampler's does: 1/(relMSE s) = spp^0.5.
    steps = lambda spps: [Step(k, [0.01 * k] * 3, [1 / (0.01 * k * k**0.5)] * 3, [0.1] * 3) for k in spps]
    bench = CaseBench(None, {"mcval/sobol": Curve("a", "render only", steps((16, 32, 64)), 0.1),
                             "mitsuba/multijitter": Curve("b", "render only", steps((16, 64)), 0.1)}, np.zeros(3))
    # Medians over their own steps would give 32^0.5 / ((16^0.5 + 64^0.5) / 2) = 0.94; the same curve is 1.
    assert bench.comparison(None)["ratio"] == pytest.approx(1.0)


def test_our_engine_in_process_renders_the_same_bits_as_the_child_process():
    """The bench renders mcval in process (warm threads, as Mitsuba's); the images must be the child's."""
    from harness.engines.mcval import McvalEngine
    for batches in (1, 3):
        child = McvalEngine(sampler="independent").render("scenes/cornell.xml", "ao", 16, batches, 7, {"res": "32"})
        inner = McvalEngine(sampler="independent", in_process=True).render("scenes/cornell.xml", "ao", 16, batches, 7,
                                                                        {"res": "32"})
        assert inner.batches.shape == child.batches.shape == (batches, 32, 32, 3)
        assert np.array_equal(inner.batches, child.batches)
        assert inner.sampler == child.sampler == "independent" and inner.seconds["render"] > 0


def test_efficiency_is_the_geometric_mean_over_steps_of_the_mean_error():
    """Steps below 16 spp are left out; each step's relMSE is the mean of its runs (the MSE), not their
    median; the steps are pooled by a geometric mean, not a median of per-step values."""
    steps = [Step(8, [9.0] * 3, [9.0] * 3, [0.0] * 3),                        # below 16 spp: ignored
             Step(16, [0.1, 0.1, 0.1], [1.0, 1.0, 4.0], [0.0] * 3),           # mean 2 (median 1)
             Step(32, [0.2, 0.2, 0.9], [1.0, 1.0, 1.0], [0.0] * 3),           # median time 0.2
             Step(64, [0.4, 0.4, 0.4], [0.25, 0.25, 0.25], [0.0] * 3)]
    curve = Curve("x", "render only", steps, 0.1)
    per_step = [1 / (2.0 * 0.1), 1 / (1.0 * 0.2), 1 / (0.25 * 0.4)]
    assert curve.efficiency() == pytest.approx(float(np.exp(np.mean(np.log(per_step)))))
    assert curve.efficiency({16, 32}) == pytest.approx(float(np.sqrt(per_step[0] * per_step[1])))
    assert curve.efficiency() != pytest.approx(float(np.median(per_step)))
