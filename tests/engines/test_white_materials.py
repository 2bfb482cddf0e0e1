"""ao reads no material: Mitsuba's copy of a scene makes every material white and opaque, keeps twosided
sides and the file's lines, and both engines then see a textured plastic floor as the environment itself."""
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness.engines.mitsuba_scene import load_scene
from harness.engines.white_materials import white_materials

SCENE = """<scene version="3.0.0">
    <bsdf type="roughplastic" id="shared">
        <texture type="checkerboard" name="diffuse_reflectance"/>
    </bsdf>
    <shape type="rectangle"><ref id="shared"/></shape>
    <shape type="disk"/>
    <shape type="sphere"><ref name="interior" id="fog"/></shape>
    <shape type="cube">
        <bsdf type="twosided">
            <bsdf type="conductor"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf>
        </bsdf>
    </shape>
    <shapegroup id="group"><shape type="rectangle"><bsdf type="plastic"/></shape></shapegroup>
    <shape type="instance"><ref id="group"/></shape>
</scene>"""


def _white(bsdf: ET.Element) -> bool:
    return (bsdf.get("type") == "diffuse" and len(bsdf) == 1 and bsdf[0].get("name") == "reflectance"
            and bsdf[0].get("value") == "1")


def test_every_material_becomes_white_and_twosided_keeps_its_sides():
    root = ET.fromstring(SCENE)
    white_materials(root)
    shared = root.find("bsdf")
    assert _white(shared) and shared.get("id") == "shared"  # a <ref> still finds it
    rectangle, disk, sphere, cube, instance = root.findall("shape")
    assert rectangle.find("ref").get("id") == "shared" and rectangle.find("bsdf") is None
    assert _white(disk.find("bsdf"))  # Mitsuba would give it a diffuse one of 0.5
    assert _white(sphere.find("bsdf"))  # its <ref> names a medium, not a material
    sides = cube.find("bsdf")
    assert sides.get("type") == "twosided" and [_white(b) for b in sides] == [True, True]
    assert _white(root.find("shapegroup/shape/bsdf"))
    assert instance.find("bsdf") is None  # its members carry the materials


def test_the_files_lines_are_kept():
    root = ET.fromstring(SCENE)
    white_materials(root)
    after = ET.tostring(root, encoding="unicode")
    assert after.count("\n") == SCENE.count("\n")
    assert after.splitlines()[6].strip().startswith('<shape type="sphere">')


@pytest.fixture(scope="module")
def mi():
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    return mi


def _floor(tmp_path, material: str):
    """A floor filling the view from above, under the default environment of ao."""
    path = tmp_path / "floor.xml"
    path.write_text(f"""<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/></transform>
        {material}
    </shape>
</scene>""")
    return path


MATERIALS = ['<bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf>',
             '<bsdf type="plastic"><texture type="checkerboard" name="diffuse_reflectance"/></bsdf>',
             '<bsdf type="diffuse"><spectrum name="reflectance" value="400:0.1, 700:0.9"/></bsdf>',
             '<bsdf type="dielectric"/>']


@pytest.mark.parametrize("material", MATERIALS, ids=["gray", "textured plastic", "spectrum", "glass"])
def test_both_engines_see_the_environment_on_an_open_floor_whatever_its_material(tmp_path, mi, mcval, material):
    path = _floor(tmp_path, material)
    theirs = np.array(mi.render(load_scene(path, "ao")))[..., :3]
    np.testing.assert_allclose(theirs, 1.0, rtol=1e-6)  # the film's weighted sums round
    ours = mcval.render(str(path), "ao", 8, 2, 0).batches
    np.testing.assert_allclose(ours, 1.0, rtol=1e-6)
