"""Mitsuba 3 -> Nori, one test per element of the translation (harness/engines/nori/to_nori.py), written as an
engine file with scene_format = "nori" gets it; what Nori cannot express is refused in one line."""
import math
import xml.etree.ElementTree as ET

import pytest

from harness.engines.nori.lined_xml import NoriSceneError
from harness.engines.nori.obj_shapes import OBJ_TEXT
from harness.engines.nori.to_nori import written_nori_scene
from harness.images.suite import SCENES_DIR

SENSOR = '<sensor type="perspective"><float name="fov" value="40"/></sensor>'


def write(tmp_path, body="", sensor=SENSOR, mcval="normals", theirs="normals", params=None):
    """(Nori's scene root, width, height, OBJ files) of a Mitsuba scene made of `sensor` and `body`."""
    path = tmp_path / "scene.xml"
    path.write_text(f'<scene version="3.0.0">\n{sensor}\n{body}\n</scene>\n')
    text, width, height, files = written_nori_scene(path, params or {}, mcval, theirs, 4)
    return ET.fromstring(text), width, height, files


def refused(tmp_path, match, **parts):
    with pytest.raises(NoriSceneError, match=match) as e:
        write(tmp_path, **parts)
    assert str(e.value).startswith(f"{tmp_path / 'scene.xml'}:") and "\n" not in str(e.value)
    return str(e.value)


def props(e):
    return {c.get("name"): c.get("value") for c in e if c.get("name") and c.tag != "transform"}


def test_the_camera_writes_what_nori_would_default_differently(tmp_path):
    root, width, height, _ = write(tmp_path)
    camera = root.find("camera")
    assert props(camera) == {"fov": "40", "nearClip": "0.01", "farClip": "10000", "width": "768", "height": "576"}
    assert (width, height) == (768, 576) and root.attrib == {}  # Nori's <scene> takes no attributes
    assert camera.find("rfilter").get("type") == "gaussian" and props(camera.find("rfilter")) == \
        {"radius": "2", "stddev": "0.5"}
    assert props(root.find("sampler")) == {"sampleCount": "4"} and root.find("integrator").get("type") == "normals"


@pytest.mark.parametrize("fov, width, height, expected", [
    ('<float name="fov" value="40"/><string name="fov_axis" value="y"/>', 200, 100,
     2 * math.degrees(math.atan(2 * math.tan(math.radians(20))))),
    ('<float name="fov" value="40"/><string name="fov_axis" value="smaller"/>', 100, 200, 40),
    ('<float name="fov" value="40"/><string name="fov_axis" value="diagonal"/>', 300, 400,
     2 * math.degrees(math.atan(0.6 * math.tan(math.radians(20))))),
    ('<float name="focal_length" value="50mm"/>', 300, 400,
     2 * math.degrees(math.atan(0.6 * math.hypot(36, 24) / 100))),
])
def test_the_field_of_view_becomes_horizontal(tmp_path, fov, width, height, expected):
    sensor = f'<sensor type="perspective">{fov}<film type="hdrfilm"><integer name="width" value="{width}"/>' \
             f'<integer name="height" value="{height}"/></film></sensor>'
    root, *_ = write(tmp_path, sensor=sensor)
    assert float(props(root.find("camera"))["fov"]) == pytest.approx(expected, rel=1e-12)


def test_the_film_size_is_the_suites_resolution(tmp_path):
    root, width, height, _ = write(tmp_path, params={"res": "32"})
    assert (width, height) == (32, 32) and props(root.find("camera"))["width"] == "32"
    refused(tmp_path, "whole numbers of pixels", sensor='<sensor type="perspective"><film type="hdrfilm"><integer '
                                                        'name="width" value="0"/></film></sensor>')
    refused(tmp_path, "between 0 and 180", sensor='<sensor type="perspective"><float name="fov" value="180"/>'
                                                  '</sensor>')


@pytest.mark.parametrize("mitsuba, nori", [
    ('<rfilter type="box"/>', ("box", {})),
    ('<rfilter type="gaussian"><float name="stddev" value="0.25"/></rfilter>',
     ("gaussian", {"radius": "1", "stddev": "0.25"})),
    ('<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>', ("tent", {"radius": "1.5"})),
    ('<rfilter type="mitchell"/>', ("mitchell", {"radius": "2", "B": repr(1 / 3), "C": repr(1 / 3)})),
])
def test_the_filter_is_noris_of_the_same_shape(tmp_path, mitsuba, nori):
    root, *_ = write(tmp_path, sensor=f'<sensor type="perspective"><film type="hdrfilm">{mitsuba}</film></sensor>')
    f = root.find("camera/rfilter")
    assert (f.get("type"), props(f)) == nori


def test_a_lanczos_filter_is_refused(tmp_path):
    refused(tmp_path, "Nori's filters are", sensor='<sensor type="perspective"><film type="hdrfilm"><rfilter '
                                                   'type="lanczos"/></film></sensor>')


def test_flat_shapes_become_obj_files_beside_the_scene(tmp_path):
    body = '<shape type="rectangle"><transform name="to_world"><scale value="2"/></transform></shape>' \
           '<shape type="cube"/>'
    root, _, _, files = write(tmp_path, body)
    meshes = root.findall("mesh")
    assert [props(m)["filename"] for m in meshes] == ["rectangle_0.obj", "cube_1.obj"]
    assert files == {"rectangle_0.obj": OBJ_TEXT["rectangle"], "cube_1.obj": OBJ_TEXT["cube"]}
    assert meshes[0].find("transform").get("name") == "toWorld"
    assert meshes[0].find("transform/scale").attrib == {"value": "2, 2, 2"}


def test_a_rotation_about_a_non_unit_axis_is_refused(tmp_path):
    body = '<shape type="cube"><transform name="to_world"><rotate x="1" y="1" angle="30"/></transform></shape>'
    refused(tmp_path, "give a unit axis", body=body)
    root, *_ = write(tmp_path, body.replace('x="1" y="1"', 'x="1"'))
    assert root.find("mesh/transform/rotate").attrib == {"axis": "1, 0, 0", "angle": "30"}


@pytest.mark.parametrize("shape", ['<shape type="sphere"/>', '<shape type="disk"/>'])
def test_shapes_nori_has_no_obj_for_are_refused(tmp_path, shape):
    refused(tmp_path, "Nori's meshes are OBJ files", body=shape)


def test_the_reflectance_is_the_albedo_inline_or_by_reference(tmp_path):
    body = '<bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>' \
           '<shape type="rectangle"><ref id="red"/></shape>' \
           '<shape type="cube"><bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf></shape>' \
           '<shape type="cube"/>'
    root, *_ = write(tmp_path, body)
    assert [props(m.find("bsdf")) for m in root.findall("mesh")] == \
        [{"albedo": "0.8, 0.1, 0.1"}, {"albedo": "0.3, 0.3, 0.3"}, {"albedo": "0.5, 0.5, 0.5"}]
    refused(tmp_path, "only diffuse", body='<shape type="cube"><bsdf type="conductor"/></shape>')


def test_point_lights_are_given_by_their_power_under_simple(tmp_path):
    body = '<emitter type="point"><point name="position" value="1, 2, 3"/><rgb name="intensity" value="2"/>' \
           '</emitter><emitter type="constant"/>'
    root, *_ = write(tmp_path, body, mcval="simple", theirs="direct")
    (light,) = root.findall("emitter")
    assert light.get("type") == "point" and props(light)["position"] == "1, 2, 3"
    assert [float(v) for v in props(light)["power"].split(",")] == pytest.approx([8 * math.pi] * 3)
    normals, *_ = write(tmp_path, body)
    assert normals.findall("emitter") == []  # normals reads no emitter


def test_the_environment_is_a_full_sphere_distant_disk_under_ao(tmp_path):
    body = '<emitter type="constant"><rgb name="radiance" value="0.6"/></emitter><emitter type="point"/>'
    root, *_ = write(tmp_path, body, mcval="ao", theirs="direct_ems")
    (light,) = root.findall("emitter")
    assert light.get("type") == "distantdisk" and props(light) == {"radiance": "0.6, 0.6, 0.6", "thetaA": "180"}
    assert props(root.find("integrator")) == {"hide_emitters": "true"}  # mcval's ao: escaping rays are black


def test_direct_takes_point_lights_the_environment_and_area_lights_in_their_meshes(tmp_path):
    body = '<emitter type="point"><point name="position" value="1, 2, 3"/><rgb name="intensity" value="2"/>' \
           '</emitter><emitter type="constant"><rgb name="radiance" value="0.6"/></emitter>' \
           '<shape type="rectangle"><emitter type="area"><rgb name="radiance" value="4, 5, 6"/></emitter></shape>' \
           '<shape type="cube"/>'
    root, *_ = write(tmp_path, body, mcval="direct", theirs="direct_mis")
    assert root.find("integrator").get("type") == "direct_mis"
    assert props(root.find("integrator")) == {"hide_emitters": "false"}  # Mitsuba's direct shows the emitters
    point, disk = root.findall("emitter")
    assert point.get("type") == "point" and [float(v) for v in props(point)["power"].split(",")] == \
        pytest.approx([8 * math.pi] * 3)
    assert disk.get("type") == "distantdisk" and props(disk) == {"radiance": "0.6, 0.6, 0.6", "thetaA": "180"}
    lit, dark = root.findall("mesh")
    assert props(lit.find("emitter")) == {"radiance": "4, 5, 6"} and dark.find("emitter") is None
    # Under another integrator the area light is not written: none of the others reads it.
    ao, *_ = write(tmp_path, body, mcval="ao", theirs="direct_ems")
    assert ao.find("mesh/emitter") is None
    refused(tmp_path, "Nori's emitters are point, area", body=body + '<emitter type="spot"/>', mcval="direct",
            theirs="direct_mis")
    hidden, *_ = write(tmp_path, body + '<integrator type="path"><boolean name="hide_emitters" value="true"/>'
                                       '</integrator>', mcval="direct", theirs="direct_mis")
    assert props(hidden.find("integrator")) == {"hide_emitters": "true"}


@pytest.mark.parametrize("samples, theirs, written", [
    ('<integer name="emitter_samples" value="1"/><integer name="bsdf_samples" value="0"/>', "direct_mis", "direct_ems"),
    ('<integer name="emitter_samples" value="0"/><integer name="bsdf_samples" value="2"/>', "direct_ems", "direct_mats"),
    ('<integer name="shading_samples" value="3"/>', "direct_ems", "direct_mis"),
    ('<integer name="bsdf_samples" value="0"/>', "direct_mats", "direct_ems"),  # emitter_samples: 1 by default
    ("", "direct_ems", "direct_ems"),  # no strategy set: the engine file's name
    ('<integer name="bsdf_samples" value="0"/>', "my_direct", "my_direct"),  # not one of Nori's three
])
def test_the_scenes_own_direct_strategy_picks_noris_integrator(tmp_path, samples, theirs, written):
    body = f'<integrator type="direct">{samples}</integrator><emitter type="point"/>'
    root, *_ = write(tmp_path, body, mcval="direct", theirs=theirs)
    assert root.find("integrator").get("type") == written


def test_a_direct_integrator_without_samples_is_refused(tmp_path):
    body = '<integrator type="direct"><integer name="emitter_samples" value="0"/><integer name="bsdf_samples" ' \
           'value="0"/></integrator><emitter type="point"/>'
    refused(tmp_path, "at least one emitter or BSDF sample", body=body, mcval="direct", theirs="direct_mis")
    refused(tmp_path, "a whole number", body=body.replace('"0"/></integrator>', '"-1"/></integrator>'), mcval="direct",
            theirs="direct_mis")


def test_noris_own_simple_takes_the_light_and_the_common_albedo(tmp_path):
    body = '<emitter type="point"><point name="position" value="0, 1, 0"/><rgb name="intensity" value="2"/>' \
           '</emitter><shape type="cube"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
    root, *_ = write(tmp_path, body, mcval="simple", theirs="simple")
    assert root.findall("emitter") == [] and props(root.find("integrator"))["position"] == "0, 1, 0"
    assert [float(v) for v in props(root.find("integrator"))["energy"].split(",")] == \
        pytest.approx([4 * math.pi] * 3)
    refused(tmp_path, "differ in reflectance", body=body + '<shape type="rectangle"/>'.replace(
        "/>", '><bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf></shape>'), mcval="simple",
        theirs="simple")
    refused(tmp_path, "one point light", body=body + body.split("<shape")[0], mcval="simple", theirs="simple")


def test_noris_own_ao_needs_radiance_one_whatever_the_reflectance(tmp_path):
    ok = '<emitter type="constant"><rgb name="radiance" value="1"/></emitter>' \
         '<shape type="cube"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
    root, *_ = write(tmp_path, ok, mcval="ao", theirs="ao")
    assert root.findall("emitter") == [] and props(root.find("integrator")) == {}
    refused(tmp_path, "lights with radiance 1; this scene has 2", body=ok.replace('value="1"', 'value="2"', 1),
            mcval="ao", theirs="ao")
    refused(tmp_path, "shows nothing to a camera ray that escapes", body=ok + '<integrator type="path"><boolean '
            'name="hide_emitters" value="false"/></integrator>', mcval="ao", theirs="ao")


def test_the_suites_flat_scenes_are_written_and_its_curved_ones_refused(tmp_path):
    for name in ("plane_point", "cornell", "backfaces", "grazing_light"):
        text, *_ = written_nori_scene(SCENES_DIR / f"{name}.xml", {"res": "16"}, "simple", "direct", 2)
        assert "<mesh" in text and 'type="point"' in text
    for name in ("plane_rect_light", "real/cornell_box"):  # lit by a rectangle
        text, *_ = written_nori_scene(SCENES_DIR / f"{name}.xml", {"res": "16", "integrator": "direct"}, "direct",
                                      "direct_mis", 2)
        assert '<emitter type="area">' in text
    with pytest.raises(NoriSceneError, match=r"sphere_floor_unit.xml:\d+: <shape type=\"sphere\""):
        written_nori_scene(SCENES_DIR / "sphere_floor_unit.xml", {"res": "16"}, "normals", "normals", 2)


def test_what_nori_cannot_hold_is_refused_on_its_line(tmp_path):
    message = refused(tmp_path, "has no Nori counterpart", body='<medium type="homogeneous"/>')
    assert ":3: <medium" in message
    refused(tmp_path, "colours are RGB", body='<shape type="cube"><bsdf type="diffuse"><texture type="bitmap" '
                                              'name="reflectance"/></bsdf></shape>')
    refused(tmp_path, "refers to no top-level <bsdf>", body='<shape type="cube"><ref id="nope"/></shape>')
    refused(tmp_path, "Nori has no flip_normals", body='<shape type="cube"><boolean name="flip_normals" '
                                                       'value="true"/></shape>')
    refused(tmp_path, "one camera", sensor=SENSOR + SENSOR)
    refused(tmp_path, "Nori's camera is perspective", sensor='<sensor type="orthographic"/>')
    root, *_ = write(tmp_path, '<shape type="cube"><bsdf type="diffuse"><spectrum name="reflectance" '
                               'value="0.25"/></bsdf></shape>')
    assert props(root.find("mesh/bsdf")) == {"albedo": "0.25, 0.25, 0.25"}


def test_an_included_element_is_refused_without_a_line_of_the_wrong_file(tmp_path):
    (tmp_path / "inc.xml").write_text('<scene version="3.0.0">\n\n\n<shape type="sphere"/></scene>')
    message = refused(tmp_path, "Nori's meshes are OBJ files", body='<include filename="inc.xml"/>')
    assert message.startswith(f"{tmp_path / 'scene.xml'}: <shape type=\"sphere\">")
