"""A failure's first line names its cause: a renderer that leaves out a scene's reflectance (its image twice
the reference's), one off by pi; a reference image that holds |n| where mcval is signed (and, for a scene in
Nori's dialect, whose normals integrator writes |n|, the comparison is made that way and passes)."""
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness.cli import main
from harness.engines.registry import make_engine
from harness.exr import write_layers
from harness.images.user_scenes import prepare_scenes
from tests.helpers.foreign_renderers import write_engine


def _first_lines(out):
    case = json.loads((out / "latest" / "results.json").read_text())["images"][0]
    failure = next(ET.parse(out / "latest" / "junit.xml").iter("failure"))
    return case, failure.get("message")


@pytest.mark.parametrize("factor, case, named", [
    (2.0, "plane_ao:ao", "a factor 2 = 1/the reflectance 0.5 (left out?)"),
    (math.pi, "plane_point:simple", "a factor pi")])
def test_a_constant_factor_is_named_first(tmp_path, capsys, factor, case, named):
    engine = write_engine(tmp_path, "scaled", constants={"FACTOR": factor})
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", case, "--out", str(out)]) == 1
    result, message = _first_lines(out)
    assert result["note"].startswith(f"the test is {factor:.4f}x the reference everywhere: {named}")
    assert message.startswith(result["note"])
    printed = " ".join(capsys.readouterr().out.split())
    assert f"FAIL {case} — the test is {factor:.4f}x" in printed


NORI = """<scene>
<integrator type="normals"/>
<mesh type="obj"><string name="filename" value="quad.obj"/></mesh>
<camera type="perspective"><float name="fov" value="60"/><integer name="width" value="32"/>
<integer name="height" value="32"/></camera>
</scene>
"""
# A quad 4 in front of Nori's camera (which looks down +z), turned so that its normal has negative components.
QUAD = "v -1 -1 4.5\nv 1 -1 3.5\nv 1 1 3.5\nv -1 1 4.5\nf 4 3 2 1\n"


def test_a_reference_of_absolute_normals_is_named_and_nori_scenes_are_compared_so(tmp_path, capsys):
    nori = tmp_path / "nori"
    nori.mkdir()
    (nori / "quad.obj").write_text(QUAD)
    (nori / "tilted.xml").write_text(NORI)
    (scene,) = prepare_scenes([nori / "tilted.xml"], tmp_path / "cache", 32)
    assert scene.dialect == "nori"
    k, spp = 8, 64
    mcval = make_engine("mcval").render(str(scene.prepared), "normals", spp, k, 77, {"res": "32"}).mean
    assert mcval.min() < 0
    image = tmp_path / "nori_normals.exr"
    write_layers(image, {"RGB": np.abs(mcval)})
    # The same scene written in Mitsuba's dialect: nothing says the image holds |n|, and the failure says so.
    mitsuba = tmp_path / "mitsuba"
    mitsuba.mkdir()
    (mitsuba / "tilted.xml").write_text(scene.prepared.read_text())
    reference = ["--reference-image", str(image), "--reference-spp", str(k * spp), "--only", "normals"]
    out = tmp_path / "results_mitsuba"
    assert main(["images", "--scene", str(mitsuba / "tilted.xml"), *reference, "--out", str(out)]) == 1
    result, message = _first_lines(out)
    assert result["note"].startswith("the reference holds |n|")
    assert message.startswith("the reference holds |n|")
    printed = " ".join(capsys.readouterr().out.split())
    assert "FAIL tilted:normals — the reference holds |n|" in printed
    out = tmp_path / "results_nori"
    assert main(["images", "--scene", str(nori / "tilted.xml"), *reference, "--out", str(out)]) == 0
    (result,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert result["verdict"] == "PASS" and result["note"].startswith("compared as |n|")
