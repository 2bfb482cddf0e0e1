"""A file that is no scene mcval can render (not XML, a Nori file whose mesh is missing, no sensor) fails its
cases with one line naming the file, and the run goes on with the others."""
import json
import shutil

import pytest

from harness.closed_forms.plane_scene import NotAnalytic, load_plane_scene
from harness.images.suite import SCENES_DIR

NORI = """<?xml version='1.0' encoding='utf-8'?>
<scene>
  <integrator type="ao"/>
  <camera type="perspective">
    <float name="fov" value="40"/>
    <transform name="toWorld"><lookat target="0, 0, 0" origin="5, 5, 5" up="0, 0, 1"/></transform>
    <integer name="width" value="64"/><integer name="height" value="64"/>
  </camera>
  <mesh type="obj"><string name="filename" value="sphere.obj"/></mesh>
</scene>
"""
BAD = {"garbage": "this is not xml <<<", "nori": NORI,
       "nosensor": '<scene version="3.0.0"><shape type="rectangle"/></scene>'}


@pytest.fixture
def folder(tmp_path):
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    for name, text in BAD.items():
        (scenes / f"{name}.xml").write_text(text)
    shutil.copy(SCENES_DIR / "plane_point.xml", scenes)
    return scenes


def test_no_scene_file_is_a_closed_form_case(folder):
    for name in BAD:
        with pytest.raises(NotAnalytic):
            load_plane_scene(folder / f"{name}.xml")
    assert load_plane_scene(folder / "plane_point.xml").kind == "plane"


@pytest.mark.mitsuba
def test_each_bad_file_fails_its_case_in_one_line_and_the_run_goes_on(folder, tmp_path):
    from harness.cli import main
    out = tmp_path / "out"
    assert main(["images", "--scene", str(folder), "--only", *[f"{n}:ao" for n in BAD], "plane_point:ao",
                 "--out", str(out)]) == 1
    entries = {e["scene"]: e for e in json.loads((out / "latest" / "results.json").read_text())["images"]}
    assert entries["plane_point"]["pass"] is True
    for name in BAD:
        error = entries[name]["error"]
        assert entries[name]["pass"] is False and "\n" not in error, (name, error)
    assert "garbage.xml: not an XML scene file" in entries["garbage"]["error"]
    assert f"(the prepared copy of {folder / 'garbage.xml'})" in entries["garbage"]["error"]
