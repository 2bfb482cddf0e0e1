"""Nori -> Mitsuba 3, one test per element of the translation (harness/engines/nori/to_mitsuba.py): each
reads a correct Nori file as Nori means it, and each refusal is one line naming the file, the line and why."""
import math
import xml.etree.ElementTree as ET

import pytest

from harness.engines.nori.lined_xml import NoriSceneError
from harness.engines.nori.to_mitsuba import is_nori, nori_to_mitsuba

CAMERA = '<camera type="perspective"/>'
QUAD = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n"


def translate(tmp_path, body="", integrator='<integrator type="normals"/>', camera=CAMERA,
              notes: list | None = None) -> ET.Element:
    (tmp_path / "quad.obj").write_text(QUAD)
    (tmp_path / "smooth.obj").write_text(QUAD.replace("f 1 2 3 4", "vn 0 0 1\nf 1//1 2//1 3//1 4//1"))
    path = tmp_path / "scene.xml"
    path.write_text(f"<scene>\n{integrator}\n{camera}\n{body}\n</scene>\n")
    return nori_to_mitsuba(path.read_text(), path, notes)


def noted(tmp_path, match: str, **parts) -> tuple[ET.Element, str]:
    """The translation of a file with one element left out, and the note saying so (one line)."""
    notes: list[str] = []
    root = translate(tmp_path, notes=notes, **parts)
    (note,) = notes
    assert match in note and note.startswith(f"{tmp_path / 'scene.xml'}:") and "\n" not in note
    return root, note


def refused(tmp_path, match: str, **parts) -> str:
    with pytest.raises(NoriSceneError, match=match) as e:
        translate(tmp_path, **parts)
    message = str(e.value)
    assert message.startswith(f"{tmp_path / 'scene.xml'}:") and "\n" not in message
    return message


def props(e: ET.Element) -> dict[str, str]:
    return {c.get("name"): c.get("value") for c in e if c.get("name") and c.tag != "transform"}


def test_nori_files_are_told_from_mitsubas():
    assert is_nori(ET.fromstring("<scene><camera type='perspective'/></scene>"))
    assert is_nori(ET.fromstring("<scene><mesh type='obj'/></scene>"))
    assert is_nori(ET.fromstring("<scene><sampler type='independent'/></scene>"))
    assert is_nori(ET.fromstring("<test type='ttest'/>"))
    assert not is_nori(ET.fromstring("<scene version='3.0.0'><sensor type='perspective'><sampler "
                                     "type='independent'/></sensor><shape type='obj'/></scene>"))
    # Mitsuba's documentation scenes declare a top-level sampler that their sensor refers to.
    assert not is_nori(ET.fromstring("<scene version='2.1.0'><sampler type='independent' id='s'/></scene>"))


def test_the_camera_takes_noris_defaults(tmp_path):
    sensor = translate(tmp_path).find("sensor")
    assert props(sensor) == {"fov": "30", "fov_axis": "x", "near_clip": "0.0001", "far_clip": "10000"}
    assert props(sensor.find("film")) == {"width": "1280", "height": "720", "pixel_format": "rgb"}
    assert props(sensor.find("sampler")) == {"sample_count": "1"}


def test_the_camera_reads_its_fov_clips_size_and_to_world(tmp_path):
    camera = ('<camera type="perspective"><float name="fov" value="45"/><float name="nearClip" value="0.5"/>'
              '<float name="farClip" value="20"/><integer name="width" value="32"/><integer name="height" '
              'value="16"/><transform name="toWorld"><lookat origin="1,2,3" target="0,0,0" up="0,0,1"/>'
              '</transform></camera>')
    sensor = translate(tmp_path, camera=camera).find("sensor")
    assert props(sensor) == {"fov": "45", "fov_axis": "x", "near_clip": "0.5", "far_clip": "20"}
    assert props(sensor.find("film"))["width"] == "32" and props(sensor.find("film"))["height"] == "16"
    assert sensor.find("transform").get("name") == "to_world"
    assert sensor.find("transform/lookat").attrib == {"origin": "1, 2, 3", "target": "0, 0, 0", "up": "0, 0, 1"}


def test_a_bad_camera_is_refused_on_its_line(tmp_path):
    # A property no Nori class reads is ignored by Nori: a note says so.
    _, note = noted(tmp_path, "ignored, as Nori ignores it",
                    camera='<camera type="perspective">\n<float name="fovy" value="3"/></camera>')
    assert ':4: <float name="fovy">' in note
    message = refused(tmp_path, "reads 'fov' as a <float>, not a <integer>",
                      camera='<camera type="perspective">\n<integer name="fov" value="3"/></camera>')
    assert ":4: <integer" in message
    refused(tmp_path, "nearClip < farClip", camera='<camera type="perspective"><float name="nearClip" '
                                                    'value="5"/><float name="farClip" value="1"/></camera>')
    refused(tmp_path, "Nori's camera is perspective", camera='<camera type="thinlens"/>')
    refused(tmp_path, "needs a <camera>", camera="")
    refused(tmp_path, "needs an <integrator>", integrator="")


def test_the_filter_is_mitsubas_of_the_same_shape(tmp_path):
    def film_filter(inner):
        camera = f'<camera type="perspective">{inner}</camera>'
        return translate(tmp_path, camera=camera).find("sensor/film/rfilter")
    default = film_filter("")
    assert default.get("type") == "gaussian" and props(default) == {"stddev": "0.5"}
    wide = film_filter('<rfilter type="gaussian"><float name="stddev" value="1"/><float name="radius" '
                       'value="4"/></rfilter>')
    assert props(wide) == {"stddev": "1"}
    assert film_filter('<rfilter type="box"/>').get("type") == "box"
    assert props(film_filter('<rfilter type="tent"/>')) == {"radius": "1"}
    assert props(film_filter('<rfilter type="mitchell"/>')) == {"B": repr(1 / 3), "C": repr(1 / 3)}
    refused(tmp_path, "always reaches 4 stddev", camera='<camera type="perspective"><rfilter type="gaussian">'
                                                        '<float name="radius" value="3"/></rfilter></camera>')
    refused(tmp_path, "2 pixels wide", camera='<camera type="perspective"><rfilter type="mitchell"><float '
                                              'name="radius" value="3"/></rfilter></camera>')


def test_the_top_level_sampler_goes_into_the_sensor(tmp_path):
    root = translate(tmp_path, '<sampler type="independent"><integer name="sampleCount" value="16"/></sampler>')
    assert props(root.find("sensor/sampler")) == {"sample_count": "16"} and root.find("sampler") is None
    refused(tmp_path, "sampler is independent", body='<sampler type="stratified"/>')
    refused(tmp_path, "whole number", body='<sampler type="independent"><integer name="sampleCount" '
                                           'value="2.5"/></sampler>')


def test_an_obj_mesh_without_normals_is_shaded_flat_as_nori_shades_it(tmp_path):
    flat = translate(tmp_path, '<mesh type="obj"><string name="filename" value="quad.obj"/></mesh>').find("shape")
    assert flat.get("type") == "obj" and props(flat)["face_normals"] == "true"
    assert props(flat)["filename"] == "quad.obj"
    smooth = translate(tmp_path, '<mesh type="obj"><string name="filename" value="smooth.obj"/></mesh>')
    assert "face_normals" not in props(smooth.find("shape"))
    refused(tmp_path, "meshes are OBJ files", body='<mesh type="ply"/>')
    refused(tmp_path, "needs <string name=\"filename\">", body='<mesh type="obj"/>')


def test_the_diffuse_albedo_is_the_reflectance(tmp_path):
    def reflectance(mesh_inner, integrator='<integrator type="normals"/>'):
        body = f'<mesh type="obj"><string name="filename" value="quad.obj"/>{mesh_inner}</mesh>'
        return props(translate(tmp_path, body, integrator).find("shape/bsdf"))["reflectance"]
    assert reflectance("") == "0.5, 0.5, 0.5"
    assert reflectance('<bsdf type="diffuse"><color name="albedo" value="0.1,0.2,0.3"/></bsdf>') == "0.1, 0.2, 0.3"
    # Nori's ao and simple integrators ignore the albedo: rho = 1 computes what they do.
    assert reflectance('<bsdf type="diffuse"><color name="albedo" value="0.1,0.2,0.3"/></bsdf>',
                       '<integrator type="ao"/>') == "1, 1, 1"
    refused(tmp_path, "Nori's BSDFs are diffuse", body='<mesh type="obj"><string name="filename" value="quad.obj"/>'
                                                       '<bsdf type="plastic"/></mesh>')
    refused(tmp_path, "three finite numbers", body='<mesh type="obj"><string name="filename" value="quad.obj"/>'
                                                   '<bsdf type="diffuse"><color name="albedo" value="1,2"/></bsdf>'
                                                   '</mesh>')


@pytest.mark.parametrize("step, expected", [
    ('<translate value="1,2,3"/>', ("translate", {"x": "1", "y": "2", "z": "3"})),
    ('<scale value="2,2,0.5"/>', ("scale", {"x": "2", "y": "2", "z": "0.5"})),
    ('<rotate axis="0,0,2" angle="30"/>', ("rotate", {"x": "0", "y": "0", "z": "1", "angle": "30"})),
    ('<matrix value="1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1"/>', ("matrix", {"value": "1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1"})),
    ('<lookat origin="0,0,1" target="0,0,0" up="0,1,0"/>', ("lookat", {"origin": "0, 0, 1", "target": "0, 0, 0",
                                                                       "up": "0, 1, 0"})),
])
def test_each_transform_step_is_mitsubas(tmp_path, step, expected):
    body = f'<mesh type="obj"><string name="filename" value="quad.obj"/><transform name="toWorld">{step}' \
           '</transform></mesh>'
    (written,) = translate(tmp_path, body).find("shape/transform")
    assert (written.tag, written.attrib) == expected


def test_transform_steps_keep_their_order_and_bad_ones_are_refused(tmp_path):
    body = '<mesh type="obj"><string name="filename" value="quad.obj"/><transform name="toWorld"><scale ' \
           'value="2,2,2"/><rotate axis="1,0,0" angle="90"/><translate value="0,0,-1"/></transform></mesh>'
    assert [e.tag for e in translate(tmp_path, body).find("shape/transform")] == ["scale", "rotate", "translate"]
    for bad, why in (('<scale value="2"/>', "three finite numbers"), ('<matrix value="1 2 3"/>', "16 finite"),
                     ('<rotate axis="0,0,0" angle="3"/>', "axis is zero"), ('<shear/>', "holds only")):
        refused(tmp_path, why, body=body.replace('<scale value="2,2,2"/>', bad))


def test_an_area_light_stays_on_its_mesh(tmp_path):
    body = '<mesh type="obj"><string name="filename" value="quad.obj"/><emitter type="area"><color ' \
           'name="radiance" value="4,5,6"/></emitter></mesh>'
    emitter = translate(tmp_path, body).find("shape/emitter")
    assert emitter.get("type") == "area" and props(emitter) == {"radiance": "4, 5, 6"}
    refused(tmp_path, "belongs inside the <mesh>", body='<emitter type="area"/>')


def test_a_point_lights_power_is_four_pi_times_its_intensity(tmp_path):
    body = '<emitter type="point"><point name="position" value="0,1,2"/><color name="power" ' \
           'value="12.566370614359172,0,1"/></emitter>'
    emitter = translate(tmp_path, body).find("emitter")
    assert props(emitter)["position"] == "0, 1, 2"
    assert [float(v) for v in props(emitter)["intensity"].split(",")] == pytest.approx([1, 0, 1 / (4 * math.pi)])
    refused(tmp_path, "needs <point name=\"position\">", body='<emitter type="point"/>')


def test_a_full_sphere_distant_disk_is_a_constant_environment(tmp_path):
    body = '<emitter type="distantdisk"><color name="radiance" value="0.6,0.6,0.6"/><float name="thetaA" ' \
           'value="180"/></emitter>'
    root = translate(tmp_path, body, '<integrator type="direct_ems"/>')
    assert root.find("emitter").get("type") == "constant" and props(root.find("emitter")) == \
        {"radiance": "0.6, 0.6, 0.6"}
    # direct_ems shows the environment to camera rays, as Nori's sphere_ao reference does.
    assert root.find("integrator").get("type") == "direct" and props(root.find("integrator")) == \
        {"emitter_samples": "1", "bsdf_samples": "0", "hide_emitters": "false"}
    hidden = translate(tmp_path, body, '<integrator type="direct_mis"><boolean name="hide_emitters" '
                                       'value="true"/></integrator>')
    assert props(hidden.find("integrator"))["hide_emitters"] == "true"
    refused(tmp_path, "true or false", body=body, integrator='<integrator type="direct_mis"><boolean '
                                                          'name="hide_emitters" value="maybe"/></integrator>')
    root, _ = noted(tmp_path, "narrower than thetaA = 180", body=body.replace('"180"', '"30"'),
                    integrator='<integrator type="normals"/>')
    assert root.find("emitter") is None  # left out: only the file's own integrator would read it


AREA_LIGHT = '<mesh type="obj"><string name="filename" value="quad.obj"/><emitter type="area"><color ' \
             'name="radiance" value="4,5,6"/></emitter></mesh>'


@pytest.mark.parametrize("kind, emitter_samples, bsdf_samples", [("direct_ems", "1", "0"), ("direct_mats", "0", "1"),
                                                                  ("direct_mis", "1", "1")])
def test_noris_direct_strategies_are_mitsubas_direct_with_their_samples(tmp_path, kind, emitter_samples,
                                                                       bsdf_samples):
    notes: list[str] = []
    root = translate(tmp_path, AREA_LIGHT, f'<integrator type="{kind}"/>', notes=notes)
    integrator = root.find("integrator")
    assert integrator.get("type") == "direct" and props(integrator) == \
        {"emitter_samples": emitter_samples, "bsdf_samples": bsdf_samples, "hide_emitters": "false"}
    assert props(root.find("shape/emitter")) == {"radiance": "4, 5, 6"} and notes == []


def test_whitted_is_direct_ems_where_no_surface_is_a_mirror_or_glass(tmp_path):
    integrator = translate(tmp_path, AREA_LIGHT, '<integrator type="whitted"/>').find("integrator")
    assert integrator.get("type") == "direct" and props(integrator) == \
        {"emitter_samples": "1", "bsdf_samples": "0", "hide_emitters": "false"}
    mirror = '<mesh type="obj"><string name="filename" value="quad.obj"/><bsdf type="mirror"/></mesh>'
    _, note = noted(tmp_path, "mirror and glass", body=AREA_LIGHT + mirror, integrator='<integrator type="whitted"/>')
    assert ':2: <integrator type="whitted">: not compared' in note


@pytest.mark.parametrize("kind", ["path_mis", "direct_mats", "whitted"])
def test_a_nori_microfacet_or_glass_leaves_an_integrator_that_reads_it_uncompared(tmp_path, kind):
    """Nori's microfacet is its course's model, not Mitsuba's roughplastic: compared through that translation, a
    correct Nori renderer would fail. A mirror is Mitsuba's own (a conductor of material none) and is compared."""
    for bsdf in ('<bsdf type="microfacet"/>', '<bsdf type="dielectric"/>'):
        body = AREA_LIGHT + f'<mesh type="obj"><string name="filename" value="quad.obj"/>{bsdf}</mesh>'
        _, note = noted(tmp_path, "not compared", body=body, integrator=f'<integrator type="{kind}"/>')
        assert "no Mitsuba BSDF known to be the same" in note or kind == "whitted", note
    mirror = AREA_LIGHT + '<mesh type="obj"><string name="filename" value="quad.obj"/><bsdf type="mirror"/></mesh>'
    if kind != "whitted":
        root = translate(tmp_path, mirror, f'<integrator type="{kind}"/>')
        assert root.find("integrator").get("type") in ("path", "direct")


@pytest.mark.parametrize("kind", ["path_mats", "path_ems", "path_mis"])
def test_noris_path_tracers_are_mcvals_path_with_their_strategy(tmp_path, kind):
    notes: list[str] = []
    integrator = translate(tmp_path, AREA_LIGHT, f'<integrator type="{kind}"/>', notes=notes).find("integrator")
    assert integrator.get("type") == "path" and props(integrator) == {"strategy": kind[5:]} and notes == []
    noted(tmp_path, "the scene has no emitter", integrator=f'<integrator type="{kind}"/>')


def test_direct_lighting_from_point_lights(tmp_path):
    body = '<emitter type="point"><point name="position" value="0,1,2"/><color name="power" value="1,1,1"/>' \
           '</emitter>'
    # Nori's direct sums its point lights exactly: mcval's simple.
    assert translate(tmp_path, body, '<integrator type="direct"/>').find("integrator").get("type") == "simple"
    _, note = noted(tmp_path, "reads no other emitter; this scene has area emitters", body=body + AREA_LIGHT,
                    integrator='<integrator type="direct"/>')
    assert translate(tmp_path, body, '<integrator type="direct_ems"/>').find("integrator").get("type") == "direct"
    root, _ = noted(tmp_path, "never reaches a point light", body=body, integrator='<integrator type="direct_mats"/>')
    assert root.find("integrator").get("type") == "path" and root.find("emitter").get("type") == "point"
    # With an area light too, BSDF sampling reaches that one, as Mitsuba's direct with bsdf_samples only does.
    both = translate(tmp_path, body + AREA_LIGHT, '<integrator type="direct_mats"/>')
    assert props(both.find("integrator"))["bsdf_samples"] == "1"
    noted(tmp_path, "the scene has no emitter", integrator='<integrator type="direct_mis"/>')


def test_noris_simple_integrator_is_one_point_light_of_energy_over_four_pi(tmp_path):
    integrator = '<integrator type="simple"><point name="position" value="1,2,3"/><color name="energy" ' \
                 'value="37.69911184307752,37.69911184307752,37.69911184307752"/></integrator>'
    root = translate(tmp_path, integrator=integrator)
    assert root.find("integrator").get("type") == "simple"
    (light,) = root.findall("emitter")
    assert props(light)["position"] == "1, 2, 3"
    assert [float(v) for v in props(light)["intensity"].split(",")] == pytest.approx([3, 3, 3])
    refused(tmp_path, "needs <point name=\"position\">", integrator='<integrator type="simple"/>')


def test_noris_ao_is_pure_ambient_occlusion(tmp_path):
    root = translate(tmp_path, integrator='<integrator type="ao"/>')
    assert root.find("integrator").get("type") == "ao"
    assert [(e.get("type"), props(e)) for e in root.findall("emitter")] == [("constant", {"radiance": "1, 1, 1"})]


@pytest.mark.parametrize("kind, why", [("av", "finite `length`"),
                                       ("path", "path_mats, path_ems and path_mis"),
                                       ("photonmapper", "no such integrator")])
def test_integrators_without_an_equivalent_are_noted_on_their_line_and_the_scene_kept(tmp_path, kind, why):
    root, note = noted(tmp_path, why, integrator=f'<integrator type="{kind}"/>')
    assert f':2: <integrator type="{kind}">: not compared' in note
    assert root.find("sensor") is not None


def test_other_refusals_name_their_line(tmp_path):
    assert ":3: not valid XML" in refused(tmp_path, "not valid XML", integrator="<integrator")
    refused(tmp_path, "holds only", body='<shape type="sphere"/>')
    refused(tmp_path, "has one <integrator>", body='<integrator type="ao"/>')
    path = tmp_path / "test.xml"
    path.write_text('<test type="ttest"><scene/></test>')
    with pytest.raises(NoriSceneError, match=":1: <test type=\"ttest\">: a Nori test file, not a scene file: "
                                             "it holds 1 one-pixel scenes"):
        nori_to_mitsuba(path.read_text(), path)
    path.write_text('<test type="chi2test"><bsdf type="microfacet"/></test>')
    with pytest.raises(NoriSceneError, match="holds BSDFs for Nori's sampling tests, and no scene"):
        nori_to_mitsuba(path.read_text(), path)


@pytest.mark.parametrize("nori, mitsuba, values", [
    ('<bsdf type="microfacet"><color name="kd" value="0.1,0.2,0.3"/><float name="alpha" value="0.02"/></bsdf>',
     "roughplastic", {"distribution": "beckmann", "alpha": "0.02", "int_ior": "1.5046", "ext_ior": "1.000277",
                      "diffuse_reflectance": "0.1, 0.2, 0.3"}),
    ('<bsdf type="dielectric"><float name="intIOR" value="1.33"/></bsdf>', "dielectric",
     {"int_ior": "1.33", "ext_ior": "1.000277"}),
    ('<bsdf type="mirror"/>', "conductor", {"material": "none"})], ids=["microfacet", "dielectric", "mirror"])
def test_noris_other_bsdfs_are_mitsubas_of_the_same_kind(tmp_path, nori, mitsuba, values):
    body = f'<mesh type="obj"><string name="filename" value="quad.obj"/>{nori}</mesh>'
    bsdf = translate(tmp_path, body).find("shape/bsdf")
    assert bsdf.get("type") == mitsuba and props(bsdf) == values
