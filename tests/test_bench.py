"""Speed against error: the error measure, the fits, and the bench command's JSON."""
import json

import numpy as np
import pytest

from harness.bench.ladder import Curve, Step, relmse
from harness.images.compare import summarize


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


def test_bench_command_writes_speed_entries(tmp_path):
    from harness.cli import main
    assert main(["bench", "--only", "cornell:simple", "--engines", "mcval", "mitsuba", "--max-spp", "8",
                 "--runs", "2", "--seed-runs", "0", "--out", str(tmp_path)]) == 0
    data = json.loads((tmp_path / "bench-latest" / "results.json").read_text())
    (entry,) = data["speed"]
    assert entry["integrator"] == "simple" and entry["scene"] == "cornell"
    assert entry["efficiency_ratio"] > 0
    assert set(entry["slope"]) == set(entry["seconds"]) == {"mcval", "mitsuba"}
    assert (tmp_path / "bench-latest" / "bench.html").read_text().count("<img") == 2
