"""`calibrate --bsdfs`: correct BSDFs give sound rates over several runs, the edge BSDF's energy p-values are
uniform, the planted defects are found as often as stated, and a wrong BSDF makes the calibration fail."""
import json
from functools import partial

import numpy as np
import pytest

from harness.bsdfs.boundary import uniform_lambert
from harness.bsdfs.calibration import calibrate_bsdfs, energy_power, parse_row, sampling_power, weight_power
from harness.bsdfs.checks import energy_check, incident, draw
from harness.bsdfs.evaluate import CHECKS, check_bsdf_at, sampling_at
from harness.cli import main
from harness.commands.bsdf_section import OUR_LIBRARY, null_row_functions

SAMPLES = 20_000


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_edge_bsdf_is_a_correct_bsdf(seed):
    results = check_bsdf_at(uniform_lambert(), incident(30.0), SAMPLES, seed, 1e-3)
    assert {n: r.verdict for n, r in results.items()} == dict.fromkeys(CHECKS, "PASS"), results


def test_the_energy_check_rejects_at_its_nominal_rate_on_the_edge():
    p = np.array([energy_check(draw(uniform_lambert(), incident(30.0), 5000, s), 0.01).p_value for s in range(400)])
    for level in (0.3, 0.05):  # 400 runs: the rate within 5 standard deviations of the level
        assert abs(np.mean(p < level) - level) < 5 * np.sqrt(level * (1 - level) / len(p))


def test_the_planted_defects_are_found_as_often_as_stated():
    energy = energy_power(0.01, range(100), 5000, 11)
    assert 0.8 <= energy["found"] / energy["runs"] <= 0.98  # stated: 90 % (100 runs: about 3 standard deviations)
    assert weight_power(range(10), 5000, 12)["found"] == 10
    sampling = sampling_power(0.01, range(100), 5000, 13)
    assert 0.8 <= sampling["found"] / sampling["runs"] <= 0.98, sampling


def test_a_third_of_the_stated_sampler_defect_goes_mostly_unseen():
    """The twin of the sampling check's power figure: the figure is the smallest defect found so often, not any."""
    wi = incident(30.0)
    moved = sampling_at(uniform_lambert(), wi, 5000, 13, 0.01)[1].details["detects_mass_moved"]
    found = [sampling_at(uniform_lambert(moved=moved / 3), wi, 5000, 100 + s, 0.01)[1].p_value < 0.01
             for s in range(60)]
    assert 0.0 < moved < 0.5 and np.mean(found) < 0.5


@pytest.mark.mitsuba
def test_correct_bsdfs_against_mitsuba_are_calibrated():
    cal = calibrate_bsdfs(partial(null_row_functions, str(OUR_LIBRARY), True),
                          ["diffuse@30", "roughconductor:alpha=0.5,ggx=1@60"], 8, SAMPLES)
    assert cal.sound and not cal.failed, cal.to_json()
    assert {e.check for e in cal.pooled} == {"sampling", "energy", "reference samples"}
    assert {d.check for d in cal.deterministic} >= {"weight", "normalisation", "reciprocity", "reference values"}
    assert all(d.runs == 8 for d in cal.deterministic)
    # Rows below albedo 1 give p = 1 in every run: named, and kept out of the rates.
    assert "diffuse reflectance=0.8 at 30 degrees: energy" in cal.degenerate
    assert [e.warp for e in cal.pooled if e.check == "energy"] == ["all rows"]
    assert [len(e.p_values) for e in cal.entries if e.check == "energy"] == [8]  # the edge row alone


def test_a_wrong_bsdf_makes_the_calibration_fail(twins):
    """A BSDF that breaks reciprocity is no null: its deterministic failures are counted as false FAILs."""
    cal = calibrate_bsdfs(partial(null_row_functions, str(twins.path), False),
                          ["lambert:albedo=0.5@30", "one_sided_shadowing:albedo=0.5@30"], 3, SAMPLES)
    bad = [d for d in cal.deterministic if d.failures]
    assert not cal.sound and [(d.row.split()[0], d.check, d.failures) for d in bad] == [
        ("one_sided_shadowing", "reciprocity", 3)]


def test_a_row_that_cannot_run_fails_the_calibration_and_the_others_run(twins):
    cal = calibrate_bsdfs(partial(null_row_functions, str(twins.path), False), ["lambert:albedo=0.5@30", "nosuch@30"],
                          2, SAMPLES)
    assert not cal.sound and len(cal.failed) == 1 and "exports no BSDF nosuch" in cal.failed[0], cal.failed
    assert all(d.runs == 2 for d in cal.deterministic)


def test_the_command_writes_its_figures_and_refuses_a_row_without_an_angle(tmp_path, capsys):
    out = tmp_path / "r"
    args = ["calibrate", "--bsdfs", "--bsdf", "diffuse@60", "--seeds", "3", "--samples", str(SAMPLES), "--no-mitsuba"]
    assert main([*args, "--out", str(out)]) == 0
    data = json.loads((out / "calibration-latest" / "calibration.json").read_text())
    assert "warps" not in data and "images" not in data and data["bsdfs"]["pass"]
    assert [p["check"] for p in data["bsdfs"]["power"]] == ["energy", "energy", "sampling", "sampling", "weight"]
    page = (out / "calibration-latest" / "calibration.html").read_text()
    assert "Calibration of the BSDF checks" in page and "planted defect" in page
    assert main(["calibrate", "--bsdfs", "--bsdf", "diffuse", "--out", str(out)]) == 2
    assert "expected NAME[:p=v,...]@DEGREES" in capsys.readouterr().err
    with pytest.raises(ValueError, match="degrees from 0 to 180"):
        parse_row("diffuse@200")
