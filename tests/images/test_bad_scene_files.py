"""Scene files nobody here wrote, each breaking a stage of `images --scene` (not XML, a Nori file whose mesh is
missing, a <default> without a value, a film size that is no number of pixels, a 1 MB tag name, 2,000 nested
BSDFs, an element the engines refuse, a missing mesh): each fails its own cases with one line naming the file
and line, and the run goes on with the others, in subfolders too."""
import json
import shutil
import time
import xml.etree.ElementTree as ET

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
PLANE = (SCENES_DIR / "plane_point.xml").read_text()


def _plane(old: str, new: str) -> str:
    assert old in PLANE
    return PLANE.replace(old, new)


def _line(text: str, part: str) -> int:
    """The line of `text` that `part` starts on."""
    return text[:text.index(part)].count("\n") + 1


WIDTH = '<integer name="width" value="$res"/>'
CONSTANT = '<emitter type="constant">'
MESH = '<shape type="ply"><string name="filename" value="meshes/none.ply"/></shape>\n'
#: name -> (file text, the text of the element its error names, or None where the error has no line)
BAD = {
    "garbage": ("this is not xml <<<", "this"),
    "nori": (NORI, None),
    "nodefault": (_plane('<default name="res" value="128"/>', '<default name="res"/>'), '<default name="res"/>'),
    "nonnumber": (_plane(WIDTH, '<integer name="width" value="abc"/>'), 'value="abc"'),
    "negative": (_plane(WIDTH, '<integer name="width" value="-5"/>'), 'value="-5"'),
    "bigtag": (_plane(CONSTANT, "<" + "a" * 1_000_000 + "/>\n" + CONSTANT), "<aaa"),
    "deep": (_plane(CONSTANT, "<!-- the first -->" + '<bsdf type="diffuse">\n' * 2000 + "</bsdf>" * 2000 + CONSTANT),
             "<!-- the first -->"),
    "unknown": (_plane('<rgb name="reflectance"', '<foo name="x"/>\n<rgb name="reflectance"'), "<foo"),
    "nomesh": (_plane(CONSTANT, MESH + CONSTANT), MESH),
}


@pytest.fixture
def folder(tmp_path):
    scenes = tmp_path / "scenes"
    (scenes / "deeper" / "still").mkdir(parents=True)
    for k, (name, (text, _)) in enumerate(BAD.items()):
        (scenes / ("deeper" if k % 2 else "") / f"{name}.xml").write_text(text)
    shutil.copy(SCENES_DIR / "plane_point.xml", scenes / "deeper" / "still")
    (scenes / ".hidden").mkdir()
    (scenes / ".hidden" / "ignored.xml").write_text("not looked at")
    return scenes


def test_no_scene_file_is_a_closed_form_case(folder):
    for name in ("garbage", "nori"):
        with pytest.raises(NotAnalytic):
            load_plane_scene(next(folder.rglob(f"{name}.xml")))
    assert load_plane_scene(folder / "deeper" / "still" / "plane_point.xml").kind == "plane"


@pytest.mark.mitsuba
def test_each_bad_file_fails_its_cases_in_one_line_and_the_run_goes_on(folder, tmp_path):
    from harness.cli import main
    out = tmp_path / "out"
    start = time.perf_counter()
    assert main(["images", "--scene", str(folder), "--only", *[f"{n}:normals" for n in BAD], "plane_point:normals",
                 "--resolution", "24", "--out", str(out)]) == 1
    assert time.perf_counter() - start < 120  # the 1 MB tag name is printed bounded, not highlighted for minutes
    results = json.loads((out / "latest" / "results.json").read_text())
    entries = {e["scene"]: e for e in results["images"]}
    assert set(entries) == {*BAD, "plane_point"}
    assert entries["plane_point"]["pass"] is True
    for name, (text, part) in BAD.items():
        error = entries[name]["error"]
        assert entries[name]["pass"] is False and "\n" not in error and len(error) < 1000, (name, error)
        assert "Traceback" not in error and "RecursionError" not in error, (name, error)
        source = str(next(folder.rglob(f"{name}.xml")))
        where = source if part is None else f"{source}:{_line(text, part) + (99 if name == 'deep' else 0)}"
        assert where in error, (name, error)
    assert "sphere.obj" in entries["nori"]["error"]
    ET.parse(out / "latest" / "junit.xml")  # well-formed whatever the files held
