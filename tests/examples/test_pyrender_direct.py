"""The example renderer's `direct` (examples/renderer/pyrender_direct.py), mapped by its engine file, through
the suites a user runs: the lit planes against their closed forms (quick, at 16 pixels) and against Mitsuba
(slow, at 32), the invariances and the bench (slow, at the suite's size); each planted mistake of a direct integrator (a light
pdf left in area measure, a BSDF without its cosine) fails the image suite."""
import json
import subprocess
from pathlib import Path

import pytest

from harness.cli import main
from tests.helpers.pyrender_engine import EXAMPLE, pyrender_engine

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _run(tmp_path, *args: str) -> tuple[int, dict]:
    out = tmp_path / "results"
    code = main([*args, "--out", str(out)])
    return code, json.loads((out / "latest" / "results.json").read_text())


def _small(tmp_path, engine: Path, scene: str = "plane_rect_light") -> tuple[int, dict]:
    """images of one lit plane under direct, 16 pixels wide, against its closed form alone."""
    return _run(tmp_path, "images", "--engine", str(engine), "--scene", str(SCENES / f"{scene}.xml"),
                "--resolution", "16", "--reference", "analytic", "--only", f"{scene}:direct")


def test_direct_matches_the_closed_form_of_a_rectangle_light(tmp_path):
    code, results = _small(tmp_path, pyrender_engine(tmp_path))
    (entry,) = results["images"]
    assert code == 0 and entry["pass"] and entry["engine"] == "pyrender", entry


@pytest.mark.parametrize("bug", ["area-pdf", "direct-no-cosine"])
def test_each_planted_direct_bug_fails_against_the_closed_form(tmp_path, bug):
    code, results = _small(tmp_path, pyrender_engine(tmp_path, bug))
    (entry,) = results["images"]
    assert code == 1 and not entry["pass"] and entry["engine"] == f"pyrender-{bug}"


CUBE_LIGHT = """<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    </sensor>
    <shape type="cube"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
</scene>
"""


def test_direct_refuses_a_light_it_does_not_model_in_one_line(tmp_path):
    scene = tmp_path / "cube_light.xml"
    scene.write_text(CUBE_LIGHT)
    res = subprocess.run([str(EXAMPLE / "pyrender"), str(scene), "--integrator", "direct", "--spp", "1", "--seed", "0",
                          "--width", "8", "--height", "8", "-o", str(tmp_path / "out.exr")],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 1 and not (tmp_path / "out.exr").exists()
    assert res.stderr.strip().splitlines() == [
        f"pyrender: error: {scene}: direct does not render this scene: it has an area light on a Cube "
        "(pyrender's direct samples area lights on Rectangle, Disk, Sphere only)"]


@pytest.mark.parametrize("integrator, refused", [("direct", True), ("path", True), ("simple", True), ("ao", False)])
def test_a_glossy_or_specular_surface_is_refused_where_the_material_is_read(tmp_path, integrator, refused):
    """It shades every surface as Mitsuba's diffuse: the materials scene's mirrors, glass and plastics would be
    rendered as something else, so direct, path and simple refuse them in one line; ao reads no material."""
    out = tmp_path / "out.exr"
    res = subprocess.run([str(EXAMPLE / "pyrender"), str(SCENES / "materials.xml"), "--integrator", integrator,
                          "--spp", "1", "--seed", "0", "--width", "8", "--height", "8", "-o", str(out)],
                         capture_output=True, text=True, timeout=300)
    if refused:
        assert res.returncode == 1 and not out.exists()
        (line,) = res.stderr.strip().splitlines()
        assert line.endswith("BSDF: this renderer models diffuse surfaces only") and "Conductor" in line, line
    else:
        assert res.returncode == 0 and out.exists(), res.stderr


@pytest.mark.slow
@pytest.mark.mitsuba
def test_direct_passes_against_mitsuba_and_the_closed_forms(tmp_path):
    scenes = ("plane_rect_light", "plane_disk_light", "plane_sphere_light")
    files = [arg for scene in scenes for arg in ("--scene", str(SCENES / f"{scene}.xml"))]
    code, results = _run(tmp_path, "images", "--engine", str(pyrender_engine(tmp_path)), *files, "--resolution", "32",
                         "--only", "direct")
    assert code == 0 and len(results["images"]) == 3
    for entry in results["images"]:
        assert entry["pass"] and set(entry["tests"]) == {"mitsuba", "analytic"}, entry


def _sphere_light(tmp_path, engine: Path, seed: int = 0) -> dict:
    """images of the sphere-lit plane under direct, 32 pixels wide, against Mitsuba: its one entry."""
    code, results = _run(tmp_path, "images", "--engine", str(engine), "--scene",
                         str(SCENES / "plane_sphere_light.xml"), "--resolution", "32", "--only", "direct",
                         "--seed", str(seed))
    (entry,) = results["images"]
    assert code == (0 if entry["pass"] else 1)
    return entry


@pytest.mark.slow
def test_another_estimator_fails_on_noise_unless_its_engine_file_declares_it(tmp_path):
    """A sphere light sampled by area (pyrender --sphere-sampling area) is unbiased and far noisier than
    Mitsuba's cone sampling, which Mitsuba's reference draws: undeclared, the noise check fails it."""
    entry = _sphere_light(tmp_path, pyrender_engine(tmp_path, sphere_by_area=True))
    variance = entry["tests"]["mitsuba"]["variance"]
    assert not entry["pass"] and variance["same_estimator"] and variance["verdict"] == "FAIL", variance
    assert variance["summary"].startswith("noise beyond the estimator's"), variance["summary"]


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_another_estimator_declared_is_judged_by_its_mean_and_passes(tmp_path, seed):
    entry = _sphere_light(tmp_path, pyrender_engine(tmp_path, sphere_by_area=True, other_estimators=("direct",)),
                          seed)
    variance = entry["tests"]["mitsuba"]["variance"]
    assert entry["pass"] and not variance["same_estimator"] and variance["verdict"] == "WARN", variance


@pytest.mark.slow
def test_a_declared_other_estimator_with_a_wrong_light_pdf_still_fails(tmp_path):
    engine = pyrender_engine(tmp_path, "area-pdf", sphere_by_area=True, other_estimators=("direct",))
    entry = _sphere_light(tmp_path, engine)
    mean_tests = entry["tests"]["mitsuba"]["tests"]
    assert not entry["pass"] and not any(t["pass"] for t in mean_tests), mean_tests


@pytest.mark.slow
def test_direct_keeps_its_invariances(tmp_path):
    code, results = _run(tmp_path, "invariance", "--engine", str(pyrender_engine(tmp_path)), "--only",
                         "plane_rect_light:direct", "light", "--no-mitsuba")
    cells = results["invariance"]["cells"]
    assert code == 0 and cells and all(c["pass"] and c["integrator"] == "direct" for c in cells), cells


@pytest.mark.slow
@pytest.mark.mitsuba
def test_direct_is_benchmarked(tmp_path):
    code, results = _run(tmp_path, "bench", "--only", "plane_rect_light:direct", "--engines",
                         str(pyrender_engine(tmp_path)), "mitsuba", "--same-sampler", "--max-spp", "2", "--runs", "2",
                         "--throughput-runs", "0", "--seed-runs", "0")
    assert code == 0, results
    [case] = results["speed"]
    assert (case["scene"], case["integrator"]) == ("plane_rect_light", "direct")
    assert set(case["efficiency"]) == {"pyrender/independent", "mitsuba/independent"}
