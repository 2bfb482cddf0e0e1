"""Every scene file loads and renders in Mitsuba 3 with each of our integrators,
through the harness's translation of our integrators into Mitsuba's."""

from __future__ import annotations

import importlib.util
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from harness.engines.mitsuba_scene import ROBUST, load_scene, mitsuba_xml
from harness.images.suite import INTEGRATORS

SCENES = Path(__file__).resolve().parents[2] / "scenes"
SCENE_FILES = sorted(p for p in SCENES.glob("*.xml") if not p.name.startswith("."))


@pytest.fixture(scope="module")
def meshes():
    spec = importlib.util.spec_from_file_location("generate_meshes", SCENES / "generate_meshes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.main(["--out", str(SCENES / "meshes"), "--quiet"]) == 0


@pytest.fixture(scope="module")
def mi():
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    return mi


def test_there_are_scenes():
    names = {p.name for p in SCENE_FILES}
    assert {"cornell.xml", "sphere_plane.xml", "highpoly.xml"} <= names


def _applicable_cases():
    """Every scene with every integrator that applies to it (simple on a plane lit by an area light does not:
    tests/images checks such a case is refused)."""
    from harness.integrators import entry

    return [pytest.param(path, name, id=f"{path.stem}-{name}") for path in SCENE_FILES for name in INTEGRATORS
            if not entry(name).not_applicable(path)]


@pytest.mark.parametrize("path, integrator", _applicable_cases())
def test_scene_renders_in_mitsuba(path, integrator, meshes, mi):
    text = path.read_text()
    # The furnace names path, whose max_depth it sets; the mapping replaces it as it replaces $integrator.
    assert 'type="$integrator"' in text or '<integrator type="path">' in text
    scene = load_scene(path, integrator, spp=4, res=32)
    image = np.array(mi.render(scene, seed=0))
    assert image.shape[:2] == (32, 32)
    assert np.isfinite(image).all()
    rgb = image[..., :3]
    # Much of the image sees the geometry, not only a few pixels.
    assert (np.abs(rgb).max(axis=-1) > 0).mean() > 0.25


def test_emitters_no_integrator_uses_are_removed_as_our_loader_skips_them():
    from harness.engines.mitsuba_scene import mitsuba_xml
    import xml.etree.ElementTree as ET
    text = (SCENES / "plane_point.xml").read_text().replace(
        "</scene>", '<emitter type="spot"/><emitter type="directional"/><emitter type="projector"/>'
                    '<emitter type="envmap"/></scene>')
    kept = {i: [e.get("type") for e in ET.fromstring(mitsuba_xml(text, i)).findall("emitter")]
            for i in ("simple", "ao", "normals")}
    assert kept == {"simple": ["point"], "ao": ["constant"], "normals": []}


@pytest.mark.parametrize("integrator", ["simple", "ao", "normals"])
def test_area_emitters_in_shapes_leave_mitsubas_copy_where_our_loader_skips_them(integrator):
    """mcval skips an area emitter inside a shape under each of these integrators (point lights only, or none):
    Mitsuba's copy drops it too, and keeps its shape."""
    import xml.etree.ElementTree as ET

    text = (SCENES / "plane_point.xml").read_text().replace(
        '<ref id="floor"/>', '<ref id="floor"/><emitter type="area"><rgb name="radiance" value="3"/></emitter>')
    root = ET.fromstring(mitsuba_xml(text, integrator))
    assert not [e for shape in root.iter("shape") for e in shape if e.tag == "emitter"]
    assert len(list(root.iter("shape"))) == 1


def test_robust_sets_embrees_robust_intersections_once(mi):
    """`mitsuba-robust`'s scenes: the property set true, a file's own value replaced, and Mitsuba takes it."""
    text = (SCENES / "plane_ao.xml").read_text().replace(
        "</scene>", '<boolean name="embree_use_robust_intersections" value="false"/></scene>')
    found = [e for e in ET.fromstring(mitsuba_xml(text, "ao", robust=True)) if e.get("name") == ROBUST]
    assert [e.get("value") for e in found] == ["true"]
    assert not [e for e in ET.fromstring(mitsuba_xml(text, "ao")) if e.get("value") == "true" and
                e.get("name") == ROBUST]
    assert load_scene(SCENES / "plane_ao.xml", "ao", robust=True, res="8") is not None


def test_the_robust_engine_is_named_and_versioned_apart():
    from harness.engines.registry import make_engine

    robust, native = make_engine("mitsuba-robust"), make_engine("mitsuba-native")
    assert robust.name == "mitsuba-robust" and robust.native and robust.robust and not native.robust
    assert "robust" in robust.version() and "robust" not in native.version()
    result = robust.render(str(SCENES / "plane_ao.xml"), "ao", 2, 1, 0, {"res": "8"})
    assert result.batches.shape == (1, 8, 8, 3) and np.isfinite(result.batches).all()


def test_a_parameterised_integrator_type_keeps_the_files_values():
    """`<integrator type="$integrator">` with a default of path is a path integrator to our loader and to Mitsuba:
    its max_depth reaches Mitsuba's copy and a strategy copy. Read as the literal "$integrator", it was dropped
    and Mitsuba traced paths without a limit where ours stopped at 8: a false FAIL on glass."""
    from harness.engines.written_scene import file_parameters

    text = ('<scene version="3.0.0"><default name="integrator" value="path"/>'
            '<integrator type="$integrator"><integer name="max_depth" value="8"/></integrator></scene>')
    mapped = ET.fromstring(mitsuba_xml(text, "path")).find("integrator")
    assert {e.get("name"): e.get("value") for e in mapped}["max_depth"] == "8"
    assert [e.get("value") for e in file_parameters(ET.fromstring(text), "path", ("max_depth",))] == ["8"]
    # Another integrator's properties are not path's.
    other = text.replace('value="path"', 'value="direct"')
    assert {e.get("name"): e.get("value") for e in ET.fromstring(mitsuba_xml(other, "path")).find("integrator")
            }["max_depth"] == "-1"
    assert file_parameters(ET.fromstring(other), "path", ("max_depth",)) == []


def test_the_integrator_a_moment_integrator_wraps_gives_its_values():
    """Mitsuba's test scenes wrap theirs in `moment` (which adds each pixel's second moment): the wrapped path's
    max_depth is the file's, for Mitsuba's copy and the strategy copies alike, as our loader reads it."""
    from harness.engines.written_scene import file_parameters

    text = ('<scene version="3.0.0"><default name="integrator" value="path"/><integrator type="moment">'
            '<integrator type="$integrator"><integer name="max_depth" value="2"/></integrator></integrator></scene>')
    mapped = ET.fromstring(mitsuba_xml(text, "path")).find("integrator")
    assert mapped.get("type") == "path" and {e.get("name"): e.get("value") for e in mapped}["max_depth"] == "2"
    assert [e.get("value") for e in file_parameters(ET.fromstring(text), "path", ("max_depth",))] == ["2"]
    assert file_parameters(ET.fromstring(text), "direct", ("max_depth",)) == []


def test_a_masks_checkerboard_opacity_is_swapped_for_mitsuba():
    """Mitsuba's checkerboard read as one value (a mask's opacity) swaps its colours: its copy swaps them back,
    given ones keeping their element, defaults written out."""
    from harness.engines.mitsuba_scene import checkerboard_opacities

    root = ET.fromstring('<scene><bsdf type="mask"><texture name="opacity" type="checkerboard">'
                         '<float name="color0" value="1"/></texture><bsdf type="diffuse"/></bsdf>'
                         '<bsdf type="diffuse"><texture name="reflectance" type="checkerboard">'
                         '<float name="color0" value="1"/></texture></bsdf></scene>')
    checkerboard_opacities(root)
    opacity, reflectance = root.iter("texture")
    assert {e.get("name"): e.get("value") for e in opacity} == {"color1": "1", "color0": "0.2"}
    assert {e.get("name"): e.get("value") for e in reflectance} == {"color0": "1"}


@pytest.mark.mitsuba
def test_mitsubas_checkerboard_read_as_one_value_swaps_its_colours():
    """The finding the swap answers: where eval gives color0, eval_1 gives color1 (Mitsuba 3.9). When Mitsuba
    mends it this test fails, and the swap must go."""
    import drjit as dr
    import mitsuba as mi

    previous = mi.variant()
    mi.set_variant("scalar_rgb")
    try:
        texture = mi.load_dict({"type": "checkerboard", "color0": 1.0, "color1": 0.0})
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.uv = mi.Point2f(0.1, 0.1)
        assert texture.eval(si)[0] == 1.0 and texture.eval_1(si) == 0.0
    finally:
        if previous:
            mi.set_variant(previous)
