"""The image run end to end: references with provenance, results.json, junit.xml, and a report
that renders in headless Chromium."""
import json
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import harness.images.references as refs
from harness.cli import main
from harness.images.suite import ImageCase, select_cases
from tests.helpers.registered_integrators import PRODUCT

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def test_references_are_reused_only_while_their_provenance_matches(mitsuba, tmp_path, monkeypatch):
    monkeypatch.setattr(refs, "REFERENCES_DIR", tmp_path)
    case = ImageCase("plane_point", "normals")
    fresh = refs.render_reference(case, mitsuba)
    refs.write_reference(case, mitsuba, fresh)
    stored, why = refs.load_reference(case, mitsuba)
    assert why == "stored reference"
    assert np.allclose(stored.summary.pixel.mean, fresh.summary.pixel.mean)
    assert np.allclose(stored.summary.tile.var_of_mean, fresh.summary.tile.var_of_mean)
    provenance = json.loads((tmp_path / mitsuba.name / "plane_point" / "normals.json").read_text())["provenance"]
    assert {"scene_sha256", "engine", "spp", "batches", "seed"} <= set(provenance)
    monkeypatch.setattr(refs, "scene_hash", lambda path: "edited")
    stale, why = refs.load_reference(case, mitsuba)
    assert stale is None and "scene_sha256 changed" in why


def test_select_cases():
    assert [c.key for c in select_cases(["cornell:ao"])] == ["cornell:ao"]
    assert {c.integrator for c in select_cases(["plane_point"])} == set(PRODUCT)
    with pytest.raises(ValueError, match="unknown scene"):
        select_cases(["atlantis"])


@pytest.fixture(scope="module")
def image_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("results")
    code = main(["images", "--only", "plane_point", "cornell:normals", "--out", str(out)])
    return code, (out / "latest").resolve()


@pytest.mark.slow
def test_images_command_writes_results_and_junit(image_run):
    code, run = image_run
    assert code == 0
    data = json.loads((run / "results.json").read_text())
    assert data["pass"] is True
    entries = {(e["scene"], e["integrator"]): e for e in data["images"]}
    assert set(entries) == {("plane_point", i) for i in PRODUCT} | {("cornell", "normals")}
    e = entries[("plane_point", "simple")]
    assert {"integrator", "scene", "pass", "tests", "metrics", "seconds"} <= set(e)
    assert set(e["tests"]) == {"mitsuba", "analytic"}  # the closed form is a second reference
    assert {t["scale"] for t in e["tests"]["mitsuba"]["tests"]} == {"pixel", "tile", "image"}
    assert {"mse", "rmse", "relmse", "smape", "psnr", "ssim", "flip_mean", "flip_p95", "ciede2000_mean",
            "mean_ratio"} <= set(e["metrics"])
    suites = ET.parse(run / "junit.xml").getroot()
    assert sum(int(s.get("tests")) for s in suites) == len(PRODUCT) + 1  # plane_point under each, cornell:normals
    assert not any(s.get("failures") != "0" for s in suites)


@pytest.mark.slow
def test_a_second_run_compares_itself_with_the_first(image_run, tmp_path):
    code, run = image_run
    out = run.parent
    # The same cases as the first run, so the same per-comparison level (fewer cases would loosen it).
    assert main(["images", "--only", "plane_point", "cornell:normals", "--out", str(out)]) == 0
    data = json.loads((out / "latest" / "results.json").read_text())
    assert data["baseline"] == run.name
    # Same code, same seed: no verdict or image mean moved. Times are left out: they are not tested.
    assert all([f for f in e["flags"] if not f.startswith("time ")] == [] for e in data["regression"])


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None, reason="needs Debian's chromium (make test installs it)")
def test_report_renders_in_headless_chromium(image_run, tmp_path):
    _, run = image_run
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={tmp_path / 'profile'}"]
    page = (run / "report.html").resolve().as_uri()
    shot = tmp_path / "report.png"
    subprocess.run([CHROMIUM, *flags, "--window-size=1280,1600", f"--screenshot={shot}", page],
                   capture_output=True, timeout=120, check=True)
    dom = subprocess.run([CHROMIUM, *flags, "--dump-dom", page], capture_output=True, text=True, timeout=120,
                         check=True).stdout
    assert "mcval validation report" in dom and dom.count("<img") >= 5
    from PIL import Image
    pixels = np.asarray(Image.open(shot).convert("RGB"), dtype=float)
    assert pixels.shape[:2] == (1600, 1280)
    assert pixels.std() > 20  # not a blank page
    # The PASS badges' green is on the page.
    green = (np.abs(pixels - [227, 246, 227]).sum(axis=-1) < 10).mean()
    assert green > 1e-4


def test_a_failing_comparison_leaves_its_data(tmp_path, mcval, mitsuba, monkeypatch):
    """A renderer that is 2% too bright fails, and the run keeps the arrays that show where."""
    import harness.engines.mcval as mcval_module

    original = mcval_module.McvalEngine.render

    def too_bright(self, *args, **kwargs):
        result = original(self, *args, **kwargs)
        result.batches = result.batches * 1.02
        return result

    monkeypatch.setattr(mcval_module.McvalEngine, "render", too_bright)
    assert main(["images", "--only", "plane_point:simple", "--out", str(tmp_path)]) == 1
    run = (tmp_path / "latest").resolve()
    data = json.loads((run / "results.json").read_text())
    assert data["pass"] is False and data["images"][0]["data"] == "images/plane_point_simple.npz"
    arrays = np.load(run / "images" / "plane_point_simple.npz")
    assert {"tested_mean", "mitsuba_mean", "mitsuba_p_pixel", "analytic_p_image"} <= set(arrays.files)
    suites = ET.parse(run / "junit.xml").getroot()
    assert any(s.get("failures") == "1" for s in suites)


def test_a_run_with_no_case_to_judge_exits_3_and_says_why(tmp_path, capsys):
    """An engine that renders simple alone, given a scene without a point light: no case runs, and the run is no
    PASS (it once printed `Results: … — PASS` and exited 0)."""
    from tests.helpers.foreign_renderers import write_engine
    from harness.images.suite import REAL_SCENES_DIR

    engine = write_engine(tmp_path, "faithful", integrators=("simple",))
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--scene", str(REAL_SCENES_DIR / "cornell_box.xml"),
                 "--out", str(out)]) == 3
    payload = json.loads((out / "latest" / "results.json").read_text())
    assert not payload["pass"] and payload["verdict"] == "NOTHING JUDGED"
    assert payload["verdict_reason"] == ("nothing was judged: image cases: no case of the engine faithful (it renders "
                                         "simple) applies to the scenes: cornell_box:simple: no point light")
    assert f"FAIL {payload['verdict_reason']}" in capsys.readouterr().out


@pytest.mark.mitsuba
def test_scenes_that_crash_or_hang_mitsuba_fail_their_own_cases_and_the_run_goes_on(tmp_path, monkeypatch, capsys):
    from harness.engines.mitsuba_worker import TIMEOUT_ENV
    from tests.engines.test_mitsuba_worker import misbehaving_scenes

    monkeypatch.setenv(TIMEOUT_ENV, "3")  # the good scene first: its worker's compilation is in its limit
    scenes = misbehaving_scenes(tmp_path)
    # Our renderer refuses the crashing file's mesh and the hanging file's filter, and a file the tested engine
    # refuses costs no reference render: mcval renders the good file in their place, so that Mitsuba is given them.
    from harness.engines.mcval import McvalEngine
    render = McvalEngine.render

    def good_in_place_of_crash(self, scene, *args, **kwargs):
        return render(self, str(scenes["good"]) if Path(scene).name in ("crash.xml", "hang.xml") else scene, *args, **kwargs)

    monkeypatch.setattr(McvalEngine, "render", good_in_place_of_crash)
    out = tmp_path / "results"
    code = main(["images", *(a for name in ("good", "crash", "hang") for a in ("--scene", str(scenes[name]))),
                 "--only", "simple", "--resolution", "8", "--out", str(out)])
    printed = " ".join(capsys.readouterr().out.split())
    assert code == 1
    results = {r["scene"]: r for r in json.loads((out / "latest" / "results.json").read_text())["images"]}
    assert results["good"]["pass"] is True
    messages = [f.get("message") for f in ET.parse(out / "latest" / "junit.xml").iter("failure")]
    for scene, line in (("crash", "Mitsuba reference: Mitsuba was killed by SIGSEGV while loading or rendering "
                                  "crash.xml"),
                        ("hang", "Mitsuba reference: Mitsuba timed out after 3 s and was killed while loading or "
                                 "rendering hang.xml")):
        assert results[scene]["pass"] is False and results[scene]["error"] == line
        assert f"FAIL {scene}:simple — {line}" in printed
        assert line in messages
