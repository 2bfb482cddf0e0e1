"""The engine registry: the only map from an engine's name to the engine. A test-only engine
(tests/plugins/engines/mcval_in_process.py, found through MCVAL_ENGINE_PATH) goes through every suite with no
edit of the harness; an unknown name is one clear error."""
import json
from pathlib import Path

import pytest

from harness.cli import main
from harness.engines.registry import engine_entries, make_engine

ROOT = Path(__file__).resolve().parents[2]
PLUGINS = ROOT / "tests" / "plugins" / "engines"


@pytest.fixture
def harness(monkeypatch):
    """`python -m harness ARGS` in this process, with the test-only engine on the engine path: its exit status."""
    monkeypatch.setenv("MCVAL_ENGINE_PATH", str(PLUGINS))
    return lambda *args: main(list(args))


def results(out: Path) -> dict:
    return json.loads(((out / "latest").resolve() / "results.json").read_text())


def test_an_unknown_engine_is_refused_with_the_known_ones(tmp_path, harness, capsys):
    with pytest.raises(ValueError, match="unknown engine 'nope': known are mcval, mitsuba"):
        make_engine("nope")
    assert harness("images", "--engine", "nope", "--only", "plane_point", "--out", str(tmp_path)) == 2
    assert "unknown engine 'nope'" in capsys.readouterr().err


def test_an_engine_file_is_found_on_the_engine_path(monkeypatch):
    monkeypatch.setenv("MCVAL_ENGINE_PATH", str(PLUGINS))
    found = engine_entries()
    assert found["mcval-in-process"].source.endswith("mcval_in_process.py")
    assert make_engine("mcval-in-process").name == "mcval-in-process"


def test_an_engine_file_without_an_engine_entry_is_an_error(tmp_path, monkeypatch):
    (tmp_path / "bad.py").write_text("ENGINE = 3\n")
    monkeypatch.setenv("MCVAL_ENGINE_PATH", str(tmp_path))
    with pytest.raises(ValueError, match="bad.py: ENGINE is a int, expected an EngineEntry"):
        engine_entries()


def test_the_reference_engine_maps_its_own_scene_files():
    from harness.engines.mitsuba import MitsubaEngine
    from harness.engines.mcval import McvalEngine

    far = ROOT / "scenes" / "far_from_origin.xml"
    assert MitsubaEngine.scene_file(MitsubaEngine.__new__(MitsubaEngine), far).name == "sphere_plane.xml"
    assert McvalEngine.scene_file(McvalEngine.__new__(McvalEngine), far) == far


@pytest.mark.slow
@pytest.mark.mitsuba
def test_the_test_engine_goes_through_images_and_invariances(tmp_path, harness):
    assert harness("images", "--engine", "mcval-in-process", "--only", "plane_point:simple", "--out", str(tmp_path)) == 0
    [case] = results(tmp_path)["images"]
    assert case["engine"] == "mcval-in-process" and case["pass"]
    assert set(case["seconds"]) == {"mcval-in-process", "mitsuba", "analytic"}
    assert harness("invariance", "--engine", "mcval-in-process", "--only", "plane_point:simple", "scale", "light",
                   "--out", str(tmp_path)) == 0
    data = results(tmp_path)["invariance"]
    assert data["gating_engine"] == "mcval-in-process"
    assert {c["engine"] for c in data["cells"]} == {"mcval-in-process", "mitsuba"}


@pytest.mark.slow
def test_the_test_engine_goes_through_warps_and_calibrate(tmp_path, harness):
    assert harness("warps", "--engine", "mcval-in-process", "--only", "tent", "--no-mitsuba", "--out", str(tmp_path)) == 0
    assert results(tmp_path)["warps"][0]["pass"]
    assert harness("calibrate", "--engine", "mcval-in-process", "--warps", "--only", "tent", "--seeds", "4",
                   "--no-mitsuba", "--out", str(tmp_path)) == 0
    cal = json.loads(((tmp_path / "calibration-latest").resolve() / "calibration.json").read_text())
    assert "in process" in cal["meta"]["engine"]


@pytest.mark.slow
@pytest.mark.mitsuba
def test_the_test_engine_is_benchmarked_against_the_reference(tmp_path, harness):
    assert harness("bench", "--engines", "mcval-in-process", "mitsuba", "--only", "cornell:simple",
                   "--same-sampler", "--max-spp", "2", "--runs", "2", "--throughput-runs", "0", "--seed-runs", "0",
                   "--out", str(tmp_path)) == 0
    [case] = results(tmp_path)["speed"]
    assert case["efficiency_ratio_same_sampler"]["tested"] == "mcval-in-process/independent"
    assert case["efficiency_ratio_same_sampler"]["reference"] == "mitsuba/independent"
