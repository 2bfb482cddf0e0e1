"""The scene rewriter of the invariance suite: the values it writes, and that both engines load every variant."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from harness.invariance.rewrite import rewrite, rotation_matrix
from harness.invariance.variants import INVARIANCES, ROTATION_AXIS, ROTATION_DEGREES

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _variant(tmp_path: Path, scene: str, kind: str, value) -> ET.Element:
    return ET.parse(rewrite(SCENES / f"{scene}.xml", tmp_path / f"{scene}.{kind}.xml", kind, value)).getroot()


def _floats(node: ET.Element) -> np.ndarray:
    return np.array([float(v) for v in node.get("value").replace(",", " ").split()])


def _prop(parent: ET.Element, name: str) -> ET.Element:
    return next(e for e in parent if e.get("name") == name)


def _steps(owner: ET.Element) -> list[ET.Element]:
    return list(_prop(owner, "to_world"))


def test_scale_appends_to_every_to_world_and_scales_lights_and_clips(tmp_path):
    root = _variant(tmp_path, "crevice", "scale", 1e-3)
    sensor = root.find("sensor")
    steps = _steps(sensor)
    # The camera conjugated, S C S^-1: rigid, as Mitsuba's cameras must be.
    assert (steps[0].tag, float(steps[0].get("value"))) == ("scale", 1e3)
    assert (steps[-1].tag, float(steps[-1].get("value"))) == ("scale", 1e-3)
    assert float(_prop(sensor, "near_clip").get("value")) == pytest.approx(1e-5)
    assert float(_prop(sensor, "far_clip").get("value")) == pytest.approx(10.0)
    shapes = list(root.iter("shape"))
    assert shapes and all(_steps(s)[-1].tag == "scale" and float(_steps(s)[-1].get("value")) == 1e-3 for s in shapes)
    mesh = next(s for s in shapes if s.get("type") == "ply")  # had no to_world: given one
    assert len(_steps(mesh)) == 1
    assert Path(_prop(mesh, "filename").get("value")).is_absolute()
    light = next(e for e in root.iter("emitter") if e.get("type") == "point")
    np.testing.assert_allclose(_floats(_prop(light, "position")), np.array([0.5, 4, 1.6]) * 1e-3)
    np.testing.assert_allclose(_floats(_prop(light, "intensity")), [40e-6] * 3)


def test_rotation_is_unit_axis_and_maps_the_light(tmp_path):
    root = _variant(tmp_path, "sphere_plane", "rotate", (ROTATION_AXIS, ROTATION_DEGREES))
    step = _steps(root.find("sensor"))[-1]
    axis = np.array([float(step.get(a)) for a in "xyz"])
    assert step.tag == "rotate" and abs(np.linalg.norm(axis) - 1) < 1e-12 and float(step.get("angle")) == 37.0
    light = next(e for e in root.iter("emitter") if e.get("type") == "point")
    expected = rotation_matrix(ROTATION_AXIS, ROTATION_DEGREES)[:3, :3] @ np.array([3.0, 5.0, 2.0])
    np.testing.assert_allclose(_floats(_prop(light, "position")), expected, rtol=1e-12)
    np.testing.assert_allclose(_floats(_prop(light, "intensity")), [80] * 3)  # a rigid motion keeps it


def test_rotation_matrix_is_mitsubas():
    mi = pytest.importorskip("harness.engines.mitsuba").load_mitsuba("scalar_rgb")
    mcval = rotation_matrix(ROTATION_AXIS, ROTATION_DEGREES)
    theirs = np.array(mi.ScalarTransform4f().rotate(list(ROTATION_AXIS), ROTATION_DEGREES).matrix)
    np.testing.assert_allclose(mcval, theirs, atol=1e-6)


def test_translation_moves_light_and_appends_step(tmp_path):
    root = _variant(tmp_path, "cornell", "translate", (10.0, -20.0, 30.0))
    assert all(_steps(s)[-1].tag == "translate" for s in root.iter("shape"))
    light = next(e for e in root.iter("emitter") if e.get("type") == "point")
    np.testing.assert_allclose(_floats(_prop(light, "position")), [10, -19.3, 30.6])


def test_light_and_reflectance_factors(tmp_path):
    root = _variant(tmp_path, "cornell", "light", 2.0)
    values = {e.get("type"): _floats(_prop(e, "intensity" if e.get("type") == "point" else "radiance"))
              for e in root.iter("emitter")}
    np.testing.assert_allclose(values["point"], [6, 6, 6])
    np.testing.assert_allclose(values["constant"], [2, 2, 2])
    root = _variant(tmp_path, "cornell", "reflectance", 0.5)
    reds = [_floats(_prop(b, "reflectance")) for b in root.iter("bsdf") if b.get("id") == "red"]
    np.testing.assert_allclose(reds[0], [0.315, 0.0325, 0.025])


def test_other_bsdfs_keep_their_values_and_a_linear_integrator_is_not_checked_on_them(tmp_path):
    """The materials scene: its floor's diffuse reflectance is halved, its conductors, glass and plastics are not.
    ao (which reads no material) is still checked for an unchanged image; an integrator linear in the diffuse
    reflectance would not be halved there, so its reflectance check is not made."""
    from harness.invariance.cell import InvarianceCase
    from harness.invariance.check import applicable

    root = _variant(tmp_path, "materials", "reflectance", 0.5)
    floor = next(b for b in root.iter("bsdf") if b.get("type") == "diffuse")  # the light's shape gets one too
    np.testing.assert_allclose(_floats(_prop(floor, "reflectance")), [0.3, 0.25, 0.2])
    plastic = next(b for b in root.iter("bsdf") if b.get("type") == "plastic")
    np.testing.assert_allclose(_floats(_prop(plastic, "diffuse_reflectance")), [0.1, 0.27, 0.36])
    names = {(s, i): [inv.name for inv in applicable(list(INVARIANCES), InvarianceCase(SCENES / f"{s}.xml", i, 4, 8))]
             for s, i in (("materials", "ao"), ("materials", "simple"), ("sphere_plane", "simple"))}
    assert "reflectance" in names[("materials", "ao")]
    assert "reflectance" not in names[("materials", "simple")] and "light" in names[("materials", "simple")]
    assert "reflectance" in names[("sphere_plane", "simple")]


def test_a_spectrum_given_per_wavelength_is_scaled_value_by_value(tmp_path):
    scene = tmp_path / "spectral.xml"
    scene.write_text('<scene version="3.0.0"><shape type="rectangle"><bsdf type="diffuse"><spectrum name="reflectance" '
                     'value="400:0.5, 700:0.8"/></bsdf><emitter type="area"><spectrum name="radiance" '
                     'value="400:2, 550:4,700:6"/></emitter></shape></scene>')
    root = ET.parse(rewrite(scene, tmp_path / "light.xml", "light", 2.0)).getroot()
    assert _prop(root.find("shape/emitter"), "radiance").get("value") == "400:4.0, 550:8.0, 700:12.0"
    root = ET.parse(rewrite(scene, tmp_path / "refl.xml", "reflectance", 0.5)).getroot()
    assert _prop(root.find("shape/bsdf"), "reflectance").get("value") == "400:0.25, 700:0.4"


def test_defaults_are_written_before_scaling(tmp_path):
    scene = tmp_path / "bare.xml"
    scene.write_text('<scene version="3.0.0"><sensor type="perspective"/>'
                     '<shape type="sphere"><point name="center" value="1, 2, 3"/><float name="radius" value="2"/></shape>'
                     '<shape type="rectangle"/><emitter type="point"/><emitter type="constant"/></scene>')
    root = ET.parse(rewrite(scene, tmp_path / "light.xml", "light", 2.0)).getroot()
    assert [_floats(_prop(e, "intensity" if e.get("type") == "point" else "radiance"))[0]
            for e in root.iter("emitter")] == [2.0, 2.0]
    root = ET.parse(rewrite(scene, tmp_path / "refl.xml", "reflectance", 0.5)).getroot()
    assert [_floats(_prop(b, "reflectance"))[0] for b in root.iter("bsdf")] == [0.25, 0.25]
    root = ET.parse(rewrite(scene, tmp_path / "scale.xml", "scale", 10.0)).getroot()
    sphere = root.find("shape")
    np.testing.assert_allclose(_floats(_prop(sphere, "center")), [10, 20, 30])
    assert float(_prop(sphere, "radius").get("value")) == 20.0
    assert [float(_prop(root.find("sensor"), n).get("value")) for n in ("near_clip", "far_clip")] == [0.1, 1e5]


def test_a_shapegroup_moves_through_its_instances(tmp_path):
    """The step goes on the instance only (on its members too it would apply twice), and no material is
    given to a shapegroup or an instance, which take none."""
    scene = tmp_path / "group.xml"
    scene.write_text("""<scene version="3.0.0">
    <shape type="shapegroup" id="g"><shape type="cube"><transform name="to_world"><scale value="0.5"/></transform>
        </shape></shape>
    <shape type="instance"><ref id="g"/><transform name="to_world"><translate value="1, 0, 0"/></transform></shape>
</scene>""")
    root = ET.parse(rewrite(scene, tmp_path / "scaled.xml", "scale", 2.0)).getroot()
    group, instance = root.findall("shape")
    assert [e.tag for e in _steps(instance)] == ["translate", "scale"]
    assert not any(e.tag == "transform" for e in group) and [e.tag for e in _steps(group.find("shape"))] == ["scale"]
    root = ET.parse(rewrite(scene, tmp_path / "darker.xml", "reflectance", 0.5)).getroot()
    group, instance = root.findall("shape")
    assert group.find("bsdf") is None and instance.find("bsdf") is None
    assert group.find("shape").find("bsdf").get("type") == "diffuse"


def test_unknown_emitters_are_refused(tmp_path):
    scene = tmp_path / "spot.xml"
    scene.write_text('<scene version="3.0.0"><emitter type="spot"/></scene>')
    with pytest.raises(ValueError, match="spot"):
        rewrite(scene, tmp_path / "out.xml", "light", 2.0)


@pytest.mark.parametrize("variant", [v for inv in INVARIANCES for v in inv.variants], ids=lambda v: v.label)
def test_both_engines_load_every_variant(tmp_path, variant):
    from harness.engines.mcval import McvalEngine
    from harness.engines.mitsuba import MitsubaEngine

    path = rewrite(SCENES / "crevice.xml", tmp_path / "crevice.variant.xml", variant.kind, variant.value)
    for engine in (McvalEngine(), MitsubaEngine()):
        out = engine.render(str(path), "ao", 1, 2, 0, {"res": "8"})
        assert out.batches.shape == (2, 8, 8, 3) and np.isfinite(out.batches).all()


def test_an_orthographic_camera_scales_with_the_scene(tmp_path, mcval):
    """Its to_world may scale, so S C scales its view; its rays' span far - near scales, near_clip stays. The
    normals image is then the same; conjugating it as a perspective camera would shrink the view by s."""
    scene = Path(__file__).resolve().parents[1] / "renderer" / "scenes" / "orthographic.xml"
    before = mcval.render(str(scene), "normals", 4, 1, 0).batches
    for s in (1e-3, 1e3):
        root = ET.parse(rewrite(scene, tmp_path / f"ortho.{s:g}.xml", "scale", s)).getroot()
        sensor = root.find("sensor")
        assert (_steps(sensor)[-1].tag, float(_steps(sensor)[-1].get("value"))) == ("scale", s)
        assert _steps(sensor)[0].tag == "scale" and _steps(sensor)[0].get("x") == "$scale"  # nothing prepended
        assert float(_prop(sensor, "near_clip").get("value")) == 0.5
        assert float(_prop(sensor, "far_clip").get("value")) == pytest.approx(0.5 + s * 49.5)
        after = mcval.render(str(tmp_path / f"ortho.{s:g}.xml"), "normals", 4, 1, 0).batches
        np.testing.assert_allclose(after, before, atol=1e-4)
