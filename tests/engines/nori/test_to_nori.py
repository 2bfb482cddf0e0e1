"""Mitsuba 3 -> Nori, one test per element of the translation (harness/engines/nori/to_nori.py), written as an
engine file with scene_format = "nori" gets it; what Nori cannot express is refused in one line."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness.engines.nori.lined_xml import NoriSceneError
from harness.engines.nori.obj_shapes import OBJ_TEXT
from harness.engines.nori.to_nori import written_nori_scene
from harness.images.suite import SCENES_DIR

SENSOR = '<sensor type="perspective"><float name="fov" value="40"/></sensor>'


def write(tmp_path, body="", sensor=SENSOR, ours="normals", theirs="normals", params=None):
    """(Nori's scene root, width, height, OBJ files) of a Mitsuba scene made of `sensor` and `body`."""
    path = tmp_path / "scene.xml"
    path.write_text(f'<scene version="3.0.0">\n{sensor}\n{body}\n</scene>\n')
    text, width, height, files = written_nori_scene(path, params or {}, ours, theirs, 4)
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


def test_an_obj_mesh_with_normals_is_named_and_one_without_is_baked_with_mitsubas(tmp_path):
    (tmp_path / "smooth.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n")
    (tmp_path / "bare.obj").write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3 4\n")
    to_world = '<transform name="to_world"><translate x="2"/></transform>'
    root, _, _, files = write(tmp_path, f'<shape type="obj"><string name="filename" value="smooth.obj"/>{to_world}'
                                        '</shape>')
    (mesh,) = root.findall("mesh")
    assert props(mesh)["filename"] == str(tmp_path / "smooth.obj") and files == {}
    assert mesh.find("transform/translate").attrib == {"value": "2, 0, 0"}
    root, _, _, files = write(tmp_path, f'<shape type="obj"><string name="filename" value="bare.obj"/>{to_world}'
                                        '</shape>')
    (mesh,) = root.findall("mesh")
    assert props(mesh)["filename"] == "obj_0.obj" and mesh.find("transform") is None
    lines = files["obj_0.obj"].splitlines()
    assert [line for line in lines if line.startswith("v ")][0] == "v 2 0 0"
    assert len([line for line in lines if line.startswith("vn ")]) == 4  # a fan of two over four corners
    assert [line for line in lines if line.startswith("f ")] == ["f 1//1 2//2 3//3", "f 1//1 3//3 4//4"]
    flat, _, _, files = write(tmp_path, '<shape type="obj"><string name="filename" value="bare.obj"/><boolean '
                                        'name="face_normals" value="true"/></shape>')
    assert props(flat.find("mesh"))["filename"] == str(tmp_path / "bare.obj") and files == {}
    # face_normals drops a file's own normals: baked without any.
    root, _, _, files = write(tmp_path, '<shape type="obj"><string name="filename" value="smooth.obj"/><boolean '
                                        'name="face_normals" value="true"/></shape>')
    assert "vn " not in files["obj_0.obj"]
    refused(tmp_path, "cannot be written as OBJ", body='<shape type="obj"><string name="filename" '
                                                       'value="missing.obj"/></shape>')


@pytest.mark.parametrize("shape", ['<shape type="sphere"/>', '<shape type="disk"/>'])
def test_shapes_nori_has_no_obj_for_are_refused(tmp_path, shape):
    refused(tmp_path, "Nori's meshes are OBJ files", body=shape)


PLY = """ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 1
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
4 0 1 2 3
"""


def test_a_ply_mesh_becomes_a_world_space_obj_with_mitsubas_normals(tmp_path):
    (tmp_path / "quad.ply").write_text(PLY)
    body = '<shape type="ply"><string name="filename" value="quad.ply"/><transform name="to_world"><rotate ' \
           'x="1" angle="90"/><translate value="0, 0, 5"/></transform></shape>'
    root, _, _, files = write(tmp_path, body)
    (mesh,) = root.findall("mesh")
    assert props(mesh)["filename"] == "ply_0.obj" and mesh.find("transform") is None
    lines = files["ply_0.obj"].splitlines()
    v = [[float(x) for x in line.split()[1:]] for line in lines if line.startswith("v ")]
    assert np.allclose(v, [[0, 0, 5], [1, 0, 5], [1, 0, 6], [0, 0, 6]], atol=1e-12)
    vn = [[float(x) for x in line.split()[1:]] for line in lines if line.startswith("vn ")]
    assert np.allclose(vn, [[0, -1, 0]] * 4, atol=1e-12)  # +z turned by 90 degrees about x
    assert [line for line in lines if line.startswith("f ")] == ["f 1//1 2//2 3//3", "f 1//1 3//3 4//4"]
    flat, _, _, files = write(tmp_path, body.replace("</shape>", '<boolean name="face_normals" value="true"/>'
                                                                    "</shape>"))
    assert "vn " not in files["ply_0.obj"] and "f 1 2 3" in files["ply_0.obj"]
    (tmp_path / "broken.ply").write_text("ply\nformat ascii 1.0\nend_header\n")
    refused(tmp_path, "cannot be written as OBJ for Nori", body=body.replace("quad.ply", "broken.ply"))


def test_computed_normals_weigh_each_triangle_by_its_angle():
    from harness.engines.nori.baked_obj import _vertex_normals
    # Vertex 0 is shared by a triangle in z = 0 with 90 degrees there and one in x = 0 with about 5.7 degrees
    # there but ten times the area: angle weighting leans to the first (+z), area weighting to the second (-x).
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 10], [0, 1, 10.0]])
    n = _vertex_normals(p, np.array([[0, 1, 2], [0, 3, 4]]))[0]
    angle = np.arccos(np.dot(p[3], p[4]) / (np.linalg.norm(p[3]) * np.linalg.norm(p[4])))
    expected = np.pi / 2 * np.array([0, 0, 1.0]) + angle * np.array([-1.0, 0, 0])
    assert n[2] > -n[0] > 0
    assert n == pytest.approx(expected / np.linalg.norm(expected))


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
    root, *_ = write(tmp_path, body, ours="simple", theirs="direct")
    (light,) = root.findall("emitter")
    assert light.get("type") == "point" and props(light)["position"] == "1, 2, 3"
    assert [float(v) for v in props(light)["power"].split(",")] == pytest.approx([8 * math.pi] * 3)
    normals, *_ = write(tmp_path, body)
    assert normals.findall("emitter") == []  # normals reads no emitter


def test_the_environment_is_a_full_sphere_distant_disk_under_ao(tmp_path):
    body = '<emitter type="constant"><rgb name="radiance" value="0.6"/></emitter><emitter type="point"/>'
    root, *_ = write(tmp_path, body, ours="ao", theirs="direct_ems")
    (light,) = root.findall("emitter")
    assert light.get("type") == "distantdisk" and props(light) == {"radiance": "0.6, 0.6, 0.6", "thetaA": "180"}
    assert props(root.find("integrator")) == {"hide_emitters": "true"}  # mcval's ao: escaping rays are black


def test_noris_own_simple_takes_the_light_and_the_common_albedo(tmp_path):
    body = '<emitter type="point"><point name="position" value="0, 1, 0"/><rgb name="intensity" value="2"/>' \
           '</emitter><shape type="cube"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
    root, *_ = write(tmp_path, body, ours="simple", theirs="simple")
    assert root.findall("emitter") == [] and props(root.find("integrator"))["position"] == "0, 1, 0"
    assert [float(v) for v in props(root.find("integrator"))["energy"].split(",")] == \
        pytest.approx([4 * math.pi] * 3)
    refused(tmp_path, "differ in reflectance", body=body + '<shape type="rectangle"/>'.replace(
        "/>", '><bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf></shape>'), ours="simple",
        theirs="simple")
    refused(tmp_path, "one point light", body=body + body.split("<shape")[0], ours="simple", theirs="simple")


def test_noris_own_ao_needs_reflectance_times_radiance_one(tmp_path):
    ok = '<emitter type="constant"><rgb name="radiance" value="2"/></emitter>' \
         '<shape type="cube"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
    root, *_ = write(tmp_path, ok, ours="ao", theirs="ao")
    assert root.findall("emitter") == [] and props(root.find("integrator")) == {}
    refused(tmp_path, "reflectance x radiance = 1", body=ok.replace('value="2"', 'value="1"'), ours="ao",
            theirs="ao")
    refused(tmp_path, "shows nothing to a camera ray that escapes", body=ok + '<integrator type="path"><boolean '
            'name="hide_emitters" value="false"/></integrator>', ours="ao", theirs="ao")


def test_the_suites_flat_scenes_are_written_and_its_curved_ones_refused(tmp_path):
    for name in ("plane_point", "cornell", "backfaces", "grazing_light"):
        text, *_ = written_nori_scene(SCENES_DIR / f"{name}.xml", {"res": "16"}, "simple", "direct", 2)
        assert "<mesh" in text and 'type="point"' in text
    with pytest.raises(NoriSceneError, match=r"sphere_floor_unit.xml:\d+: <shape type=\"sphere\""):
        written_nori_scene(SCENES_DIR / "sphere_floor_unit.xml", {"res": "16"}, "normals", "normals", 2)


STEPS = '<scale value="2, 1, 0.5"/><rotate x="1" y="1" angle="30"/><matrix value="1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1"/>' \
        '<lookat origin="1, 2, 3" target="0, 1, 0" up="0, 0, 1"/><translate x="-1"/>'


@pytest.mark.mitsuba
def test_baked_positions_are_where_mitsuba_puts_them():
    import mitsuba as mi
    from harness.engines.nori.baked_obj import transform_matrix
    mi.set_variant("scalar_rgb")
    scene = mi.load_string(f'<scene version="3.0.0"><shape type="obj" id="s"><string name="filename" '
                           f'value="{SCENES_DIR.parent / "tests/engines/nori/tri.obj"}"/><transform name="to_world">'
                           f'{STEPS}</transform></shape></scene>')
    theirs = np.array(mi.traverse(scene)["s.vertex_positions"]).reshape(-1, 3)
    m = transform_matrix(ET.fromstring(f"<transform>{STEPS}</transform>"))
    corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    assert np.allclose(corners @ m[:3, :3].T + m[:3, 3], theirs, atol=1e-5)
    swapped = transform_matrix(ET.fromstring(f"<transform>{STEPS.replace('30', '-30')}</transform>"))
    assert not np.allclose(corners @ swapped[:3, :3].T + swapped[:3, 3], theirs, atol=1e-3)


@pytest.mark.mitsuba
@pytest.mark.parametrize("kind", ["obj", "ply"])
def test_baked_normals_are_mitsubas(tmp_path, kind):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    # A bent strip of four triangles, unevenly scaled: the normals are computed in world space, angle-weighted.
    p = [(0, 0, 0), (1, 0, 0.3), (2, 0, 0), (0, 1, 0.5), (1, 1, 0), (2, 1, 0.8)]
    faces = [(0, 1, 4), (0, 4, 3), (1, 2, 5), (1, 5, 4)]
    if kind == "obj":
        (tmp_path / "strip.obj").write_text("".join(f"v {x} {y} {z}\n" for x, y, z in p) +
                                            "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces))
    else:
        (tmp_path / "strip.ply").write_text(PLY.replace("element vertex 4", "element vertex 6").replace(
            "element face 1", "element face 4").split("end_header\n")[0] + "end_header\n" +
            "".join(f"{x} {y} {z}\n" for x, y, z in p) + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces))
    to_world = '<transform name="to_world"><scale value="1, 3, 0.5"/><rotate z="1" angle="20"/></transform>'
    shape = f'<shape type="{kind}" id="s"><string name="filename" value="{tmp_path / f"strip.{kind}"}"/>' \
            f'{to_world}</shape>'
    _, _, _, files = write(tmp_path, shape)
    lines = files[f"{kind}_0.obj"].splitlines()
    ours_p = np.array([[float(x) for x in line.split()[1:]] for line in lines if line.startswith("v ")])
    ours_n = np.array([[float(x) for x in line.split()[1:]] for line in lines if line.startswith("vn ")])
    params = mi.traverse(mi.load_string(f'<scene version="3.0.0">{shape}</scene>'))
    theirs_p = np.array(params["s.vertex_positions"]).reshape(-1, 3)
    theirs_n = np.array(params["s.vertex_normals"]).reshape(-1, 3)
    order = [int(np.argmin(np.linalg.norm(ours_p - q, axis=1))) for q in theirs_p]
    assert np.allclose(ours_p[order], theirs_p, atol=1e-5)
    assert np.allclose(ours_n[order], theirs_n, atol=1e-5)
    wrong = ours_n.copy()
    wrong[1] = [0, 0, 1]  # a wrong normal at one vertex is seen
    assert not np.allclose(wrong[order], theirs_n, atol=1e-5)


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
