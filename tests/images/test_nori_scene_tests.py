"""Nori's scene tests run as they are (`images --nori-test`): furnaces in Nori's dialect, a closed box whose inside
reflects with albedo a and emits 1, under Nori's direct and path integrators (1 + a and 1 / (1 - a), as its
course's test files state them). Our renderer passes each at several seeds; a wrong reference, a planted wrong
path tracer and an integrator without a counterpart are told apart."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from harness.cli import main
from harness.engines.nori.test_files import read_nori_test
from harness.engines.registry import make_engine
from harness.images.nori_scene_tests import run_scene_test
from tests.helpers.twin_engine import TwinEngine

#: (Nori integrator, albedo, the file's reference): Nori's furnace values.
FURNACES = (("direct_ems", 0.5, 1.5), ("direct_mats", 0.8, 1.8), ("direct_mis", 0.5, 1.5), ("whitted", 0.8, 1.8),
            ("path_mats", 0.5, 2.0), ("path_ems", 0.8, 5.0), ("path_mis", 0.5, 2.0))


def _box(folder: Path) -> None:
    """box.obj: the cube [-1, 1]^3, each face wound to face inwards."""
    corners = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    lines = [f"v {x} {y} {z}" for x, y, z in corners]
    for axis in range(3):
        u, v = [a for a in range(3) if a != axis]
        for side in (-1, 1):
            quad = []
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0, 0, 0]
                p[axis], p[u], p[v] = side, a, b
                quad.append(corners.index(tuple(p)) + 1)
            # (u, v) counter-clockwise faces +axis when (axis, u, v) is cyclic: turn it to face -side.
            if ((axis + 1) % 3 == u) == (side > 0):
                quad.reverse()
            lines += [f"f {quad[0]} {quad[1]} {quad[2]}", f"f {quad[0]} {quad[2]} {quad[3]}"]
    (folder / "box.obj").write_text("\n".join(lines) + "\n")


def _scene(integrator: str, albedo: float) -> str:
    return f"""  <scene>
    <integrator type="{integrator}"/>
    <camera type="perspective">
      <float name="fov" value="10"/><integer name="width" value="1"/><integer name="height" value="1"/>
    </camera>
    <mesh type="obj">
      <string name="filename" value="box.obj"/>
      <bsdf type="diffuse"><color name="albedo" value="{albedo}, {albedo}, {albedo}"/></bsdf>
      <emitter type="area"><color name="radiance" value="1, 1, 1"/></emitter>
    </mesh>
  </scene>
"""


def _test_file(folder: Path, cases=FURNACES, samples: int = 20000) -> Path:
    _box(folder)
    path = folder / "test-furnace.xml"
    path.write_text('<?xml version="1.0"?>\n<test type="ttest">\n'
                    f'  <string name="references" value="{", ".join(str(r) for _, _, r in cases)}"/>\n'
                    f'  <integer name="sampleCount" value="{samples}"/>\n'
                    + "".join(_scene(i, a) for i, a, _ in cases) + "</test>\n")
    return path


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_renderer_passes_noris_furnaces(tmp_path, seed):
    verdicts = run_scene_test(read_nori_test(_test_file(tmp_path)), make_engine("mcval"), tmp_path, seed)
    assert [v.passed for v in verdicts] == [True] * len(FURNACES), [v.message for v in verdicts]
    assert [v.integrator for v in verdicts] == [i for i, _, _ in FURNACES]
    assert verdicts[4].message.startswith("path (20000 spp): mean ")


def _floor_test(folder: Path, integrators: tuple[str, ...]) -> tuple[Path, float]:
    """Nori's floor test as its course writes it: one ray (fov 1e-6) straight down onto a floor of albedo 0.5
    under a black rectangle emitting 1, 1 above; and the radiance there, rho / pi * E (Lambert's polygon)."""
    import numpy as np

    from harness.closed_forms.area_lights import PolygonLight, irradiance
    (folder / "floor.obj").write_text("v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nf 1 3 2\nf 1 4 3\n")
    (folder / "light.obj").write_text("v -0.5 1 -0.3\nv 0.5 1 -0.3\nv 0.5 1 0.3\nv -0.5 1 0.3\nf 1 2 3\nf 1 3 4\n")
    light = PolygonLight(np.array([[-0.5, 1, -0.3], [0.5, 1, -0.3], [0.5, 1, 0.3], [-0.5, 1, 0.3]]),
                         np.array([0.0, -1.0, 0.0]), np.ones(3))
    value = float(0.5 / np.pi * irradiance([light], np.zeros(3), np.array([0.0, 1.0, 0.0]))[0])
    scene = """  <scene>
    <integrator type="{}"/>
    <camera type="perspective">
      <transform name="toWorld"><lookat origin="0, 0.01, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
      <float name="fov" value="1e-6"/><integer name="width" value="1"/><integer name="height" value="1"/>
    </camera>
    <mesh type="obj">
      <string name="filename" value="floor.obj"/>
      <bsdf type="diffuse"><color name="albedo" value="0.5, 0.5, 0.5"/></bsdf>
    </mesh>
    <mesh type="obj">
      <string name="filename" value="light.obj"/>
      <bsdf type="diffuse"><color name="albedo" value="0, 0, 0"/></bsdf>
      <emitter type="area"><color name="radiance" value="1, 1, 1"/></emitter>
    </mesh>
  </scene>
"""
    path = folder / "test-floor.xml"
    references = ", ".join([str(value)] * len(integrators))
    path.write_text(f'<test type="ttest">\n  <string name="references" value="{references}"/>\n'
                    + "".join(scene.format(i) for i in integrators) + "</test>\n")
    return path, value


def test_noris_floor_test_looks_along_one_ray(tmp_path):
    """A camera of fov 1e-6 renders (Mitsuba's open interval, not a hundredth of a degree); whitted on diffuse
    surfaces is direct light by light samples, and path adds nothing where the floor sees only a black light."""
    integrators = ("whitted", "direct_mis", "path_mats", "path_ems", "path_mis")
    path, value = _floor_test(tmp_path, integrators)
    verdicts = run_scene_test(read_nori_test(path), make_engine("mcval"), tmp_path, 0)
    assert [v.passed for v in verdicts] == [True] * len(integrators), [v.message for v in verdicts]
    assert 0.02 < value < 0.1


def test_a_wrong_reference_fails_that_scene_only(tmp_path):
    cases = list(FURNACES)
    cases[0] = ("direct_ems", 0.5, 1.52)
    verdicts = run_scene_test(read_nori_test(_test_file(tmp_path, cases)), make_engine("mcval"), tmp_path, 0)
    assert [v.passed for v in verdicts] == [False] + [True] * (len(FURNACES) - 1)
    assert verdicts[0].p_value < verdicts[0].level


@pytest.mark.parametrize("twin", ["path_rr_undivided", "path_no_cosine", "path_double_mis"])
def test_planted_wrong_path_tracers_fail_the_path_scenes(tmp_path, twin):
    """Roulette without dividing by survival loses the light of long paths (3 % of it at albedo 0.5, 16 % at
    0.8); a missing cosine, and light a BSDF sample finds counted beside the light sample's share (the twin does
    so whatever its strategy), change every bounce. The direct scenes stay right."""
    engine = TwinEngine("path", twin, tmp_path)
    verdicts = run_scene_test(read_nori_test(_test_file(tmp_path)), engine, tmp_path, 0)
    failing = {v.integrator for v in verdicts if not v.passed}
    assert failing == {"path_mats", "path_ems", "path_mis"}


def test_an_integrator_without_a_counterpart_is_not_run(tmp_path):
    cases = (("av", 0.5, 1.5), ("direct_ems", 0.5, 1.5))
    verdicts = run_scene_test(read_nori_test(_test_file(tmp_path, cases)), make_engine("mcval"), tmp_path, 0)
    assert [v.passed for v in verdicts] == [None, True]
    assert verdicts[0].message.startswith("not run: ") and "finite `length`" in verdicts[0].message


def test_the_command_runs_the_file_and_writes_the_verdicts(tmp_path, capsys):
    path = _test_file(tmp_path)
    assert main(["images", "--nori-test", str(path), "--out", str(tmp_path / "r")]) == 0
    out = capsys.readouterr().out
    assert "Passed 7/7 tests." in out
    results = json.loads((tmp_path / "r" / "latest" / "results.json").read_text())
    assert results["verdict"] == "PASS" and len(results["nori_tests"][0]["tests"]) == 7
    assert sorted((tmp_path / "r" / "latest" / "nori_tests").iterdir())[0].name == "test-furnace-scene1.xml"


def test_a_wrong_reference_fails_the_command(tmp_path):
    cases = list(FURNACES)
    cases[5] = ("path_ems", 0.8, 4.5)
    assert main(["images", "--nori-test", str(_test_file(tmp_path, cases)), "--out", str(tmp_path / "r")]) == 1


def test_a_bsdf_test_goes_to_bsdfs_and_a_scene_test_to_images(tmp_path, capsys):
    bsdf_test = tmp_path / "chi2.xml"
    bsdf_test.write_text('<test type="chi2test"><bsdf type="diffuse"/></test>')
    assert main(["images", "--nori-test", str(bsdf_test), "--out", str(tmp_path / "r")]) == 2
    assert "run it with `bsdfs --nori-test" in capsys.readouterr().err
    assert main(["bsdfs", "--nori-test", str(_test_file(tmp_path)), "--out", str(tmp_path / "r")]) == 2
    assert "run it with `images --nori-test" in capsys.readouterr().err


def test_one_reference_per_scene(tmp_path):
    path = _test_file(tmp_path)
    path.write_text(path.read_text().replace('value="1.5, 1.8,', 'value="1.8,', 1))
    with pytest.raises(ValueError, match=r"test-furnace\.xml:2: <test type=\"ttest\">: expected one reference per "
                                         "scene: 7 scenes, 6 references"):
        read_nori_test(path)
