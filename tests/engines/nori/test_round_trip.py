"""Both directions together: Nori -> Mitsuba -> Nori -> Mitsuba gives the same scene, a Nori file of one's own
renders in both engines through the harness and they agree, and an engine file with scene_format = "nori" (a
stand-in Nori build, tests/helpers/nori_via_mcval.py) passes the suite's scenes unless a defect is planted in it."""
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from harness.engines.engine_file import EngineFileError, read_engine_file
from harness.engines.nori.to_mitsuba import nori_to_mitsuba
from harness.engines.nori.to_nori import written_nori_scene

HELPERS = Path(__file__).resolve().parents[2] / "helpers"
QUAD = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n"
NORI = """<scene>
  <sampler type="independent"><integer name="sampleCount" value="4"/></sampler>
  <integrator type="{integrator}"/>
  <mesh type="obj">
    <string name="filename" value="quad.obj"/>
    <transform name="toWorld"><scale value="3,3,1"/></transform>
    <bsdf type="diffuse"><color name="albedo" value="0.8,0.6,0.4"/></bsdf>
  </mesh>
  <mesh type="obj">
    <string name="filename" value="quad.obj"/>
    <transform name="toWorld">
      <scale value="0.5,0.5,1"/><rotate axis="1,0,0" angle="-60"/><translate value="0,0,0.6"/>
    </transform>
  </mesh>
  {emitters}
  <camera type="perspective">
    <transform name="toWorld"><lookat target="0,0,0" origin="2,-3,4" up="0,0,1"/></transform>
    <float name="fov" value="40"/>
    <integer name="width" value="48"/><integer name="height" value="32"/>
    <rfilter type="box"/>
  </camera>
</scene>
"""
EMITTERS = {"normals": "",
            "direct": '<emitter type="point"><point name="position" value="0,1,3"/><color name="power" '
                      'value="100,100,100"/></emitter>',
            "direct_ems": '<emitter type="distantdisk"><color name="radiance" value="0.6,0.6,0.6"/><float '
                          'name="thetaA" value="180"/></emitter>',
            "direct_mats": '<mesh type="obj"><string name="filename" value="quad.obj"/><transform name="toWorld">'
                           '<scale value="0.4,0.4,1"/><rotate axis="1,0,0" angle="180"/>'
                           '<translate value="0.3,0.2,1.5"/></transform>'
                           '<emitter type="area"><color name="radiance" value="6,6,6"/></emitter></mesh>'}
MCVAL_OF_NORI = {"normals": "normals", "direct": "simple", "direct_ems": "direct", "direct_mats": "direct"}


def nori_file(folder: Path, integrator: str = "normals", name: str = "quads") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "quad.obj").write_text(QUAD)
    path = folder / f"{name}.xml"
    path.write_text(NORI.format(integrator=integrator, emitters=EMITTERS.get(integrator, "")))
    return path


def canonical(root: ET.Element) -> str:
    for e in root.iter("string"):
        if e.get("name") == "filename":
            e.set("value", Path(e.get("value")).name)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode")


@pytest.mark.parametrize("integrator", sorted(EMITTERS))
def test_mitsuba_to_nori_to_mitsuba_is_the_same_scene(tmp_path, integrator):
    path = nori_file(tmp_path, integrator)
    mitsuba = nori_to_mitsuba(path.read_text(), path)
    first = tmp_path / "mitsuba.xml"
    first.write_text(ET.tostring(mitsuba, encoding="unicode"))
    # A Nori build's direct integrators named by one entry: the scene's own strategy picks which one it gets.
    theirs = "direct_mis" if MCVAL_OF_NORI[integrator] == "direct" else integrator
    text, *_ = written_nori_scene(first, {}, MCVAL_OF_NORI[integrator], theirs, 4)
    again = tmp_path / "again.xml"
    again.write_text(text)
    assert canonical(nori_to_mitsuba(text, again)) == canonical(nori_to_mitsuba(path.read_text(), path))


def test_a_changed_element_does_not_survive_as_the_same_scene(tmp_path):
    path = nori_file(tmp_path)
    mitsuba = nori_to_mitsuba(path.read_text(), path)
    next(e for e in mitsuba.iter("float") if e.get("name") == "fov").set("value", "41")
    first = tmp_path / "mitsuba.xml"
    first.write_text(ET.tostring(mitsuba, encoding="unicode"))
    text, *_ = written_nori_scene(first, {}, "normals", "normals", 4)
    assert canonical(nori_to_mitsuba(text, tmp_path / "x.xml")) != canonical(nori_to_mitsuba(path.read_text(), path))


def test_an_engine_file_may_ask_for_noris_dialect(tmp_path):
    toml = tmp_path / "nori.toml"
    toml.write_text(f'name = "nori"\ncommand = ["{sys.executable}", "{{scene}}", "{{output}}"]\n'
                    'scene_format = "nori"\n[integrators]\nnormals = "normals"\n')
    assert read_engine_file(toml).scene_format == "nori"
    toml.write_text(toml.read_text().replace('"nori"\n[', '"pbrt"\n['))
    with pytest.raises(EngineFileError, match=":3: scene_format 'pbrt' is not one of mitsuba, nori"):
        read_engine_file(toml)


@pytest.mark.slow
@pytest.mark.mitsuba
def test_a_nori_file_renders_in_both_engines_and_they_agree(tmp_path):
    from harness.cli import main
    path = nori_file(tmp_path / "in")
    out = tmp_path / "out"
    assert main(["images", "--scene", str(path), "--only", "quads:normals", "--out", str(out)]) == 0
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert entry["pass"] is True and entry["scene"] == "quads"


@pytest.mark.slow
@pytest.mark.mitsuba
def test_a_nori_file_lit_by_an_area_light_renders_its_direct_strategy_in_both_engines(tmp_path):
    from harness.cli import main
    path = nori_file(tmp_path / "in", "direct_mats", "lamp")
    out = tmp_path / "out"
    assert main(["images", "--scene", str(path), "--only", "lamp:direct", "--out", str(out)]) == 0
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert entry["pass"] is True and entry["scene"] == "lamp"


@pytest.mark.slow
@pytest.mark.mitsuba
def test_a_nori_file_whose_integrator_has_no_translation_still_renders_its_geometry(tmp_path, capsys):
    from harness.cli import main
    path = nori_file(tmp_path / "in", "path_mis", "paths")
    out = tmp_path / "out"
    assert main(["images", "--scene", str(path), "--only", "paths:normals", "--out", str(out)]) == 0
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert entry["pass"] is True
    assert f"{path}:3: <integrator type=\"path_mis\">: not compared" in capsys.readouterr().err.replace("\n", "")


@pytest.mark.slow
@pytest.mark.mitsuba
def test_a_nori_file_without_a_translation_fails_its_case_in_one_line(tmp_path):
    from harness.cli import main
    path = nori_file(tmp_path / "in", "normals", "bad")
    path.write_text(path.read_text().replace('<camera type="perspective">', '<camera type="thinlens">'))
    out = tmp_path / "out"
    assert main(["images", "--scene", str(path), "--only", "bad:normals", "--out", str(out)]) == 1
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert entry["pass"] is False and "\n" not in entry["error"]
    assert entry["error"].startswith(f"{path}:") and "Nori's camera is perspective" in entry["error"]


#: A Nori build's integrators for the suite's: emitter sampling is exact for a point light, and Nori's own ao, which
#: reads no material either, for ao.
NORI_BUILD = "normals = \"normals\"\nsimple = \"direct_ems\"\nao = \"ao\"\n"


def _engine_file(tmp_path, *bug: str, integrators: str = NORI_BUILD) -> Path:
    words = [sys.executable, str(HELPERS / "nori_via_mcval.py"), "{scene}", "{output}", "{seed}", *bug]
    toml = tmp_path / "nori.toml"
    toml.write_text(f"name = \"nori-via-mcval\"\ncommand = {json.dumps(words)}\nscene_format = \"nori\"\n"
                    f"[integrators]\n{integrators}")
    return toml


@pytest.mark.slow
@pytest.mark.mitsuba
def test_a_nori_build_renders_the_suites_scenes_written_in_its_dialect(tmp_path):
    from harness.cli import main
    out = tmp_path / "out"
    code = main(["images", "--engine", str(_engine_file(tmp_path)), "--only", "plane_point", "cornell:normals",
                 "--out", str(out)])
    entries = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert {(e["scene"], e["integrator"]) for e in entries} == \
        {("plane_point", i) for i in ("normals", "simple", "ao")} | {("cornell", "normals")}
    assert code == 0 and all(e["pass"] for e in entries)


@pytest.mark.slow
@pytest.mark.mitsuba
def test_a_nori_build_with_a_wrong_field_of_view_fails(tmp_path):
    from harness.cli import main
    out = tmp_path / "out"
    # The Cornell box's normals change with the field of view (a plane seen head-on has one normal everywhere).
    code = main(["images", "--engine", str(_engine_file(tmp_path, "--bug", "fov")), "--only", "cornell:normals",
                 "--out", str(out)])
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert code == 1 and not entry["pass"] and entry.get("error") is None  # rendered, and judged wrong


@pytest.mark.slow
@pytest.mark.mitsuba
@pytest.mark.parametrize("bug, passes", [((), True), (("--bug", "radiance"), False)])
def test_a_nori_builds_direct_integrator_renders_the_suites_area_light(tmp_path, bug, passes):
    from harness.cli import main
    out = tmp_path / "out"
    toml = _engine_file(tmp_path, *bug, integrators="direct = \"direct_mis\"\n")
    code = main(["images", "--engine", str(toml), "--only", "plane_rect_light:direct", "--out", str(out)])
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert (entry["scene"], entry["integrator"]) == ("plane_rect_light", "direct")
    assert (code == 0) is passes and entry["pass"] is passes
