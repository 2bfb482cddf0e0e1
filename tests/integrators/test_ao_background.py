"""ao shows the environment to camera rays that escape where the file's integrator says hide_emitters = false
(Mitsuba's and Nori's convention), whatever its type, and black otherwise (the suite's default): in our
renderer, in Mitsuba's mapping and in the scene an engine file's renderer is given."""
import hashlib
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness.comparison.compare import compare_batches
from harness.engines.mitsuba_scene import mitsuba_xml
from harness.engines.written_scene import written_scene

L_ENV = 0.6
K, SPP = 6, 16


def _scene(tmp_path, integrator: str) -> str:
    """A floor under the lower half of the view and sky above, under a constant emitter of radiance 0.6."""
    path = tmp_path / f"{hashlib.sha1(integrator.encode()).hexdigest()[:8]}.xml"
    path.write_text(f"""<scene version="3.0.0">
    {integrator}
    <sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 1, 4" target="0, 1, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="{SPP}"/></sampler>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/>
            <rfilter type="box"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="{L_ENV}"/></emitter>
    <shape type="rectangle">
        <transform name="to_world"><scale value="20"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>
</scene>""")
    return str(path)


SHOWN = ('<integrator type="path"><integer name="max_depth" value="3"/>'
         '<boolean name="hide_emitters" value="false"/></integrator>')
NESTED = ('<integrator type="moment"><integrator type="path"><boolean name="hide_emitters" value="false"/>'
          '</integrator></integrator>')


def _mcval(mcval, scene, seed=1):
    return mcval.render(scene, "ao", SPP, K, seed).batches


@pytest.mark.parametrize("integrator", [SHOWN, NESTED, '<integrator type="ao">'
                                        '<boolean name="hide_emitters" value="false"/></integrator>'],
                         ids=["path", "nested in moment", "ao"])
def test_an_escaping_camera_ray_sees_the_environment_when_the_file_says_so(mcval, tmp_path, integrator):
    image = _mcval(mcval, _scene(tmp_path, integrator))
    sky = image[:, :8]  # the upper third looks above the horizon
    np.testing.assert_array_equal(sky, L_ENV * np.ones_like(sky))
    # Nothing occludes the floor, whose reflectance 0.5 ao does not read: it sees the whole environment.
    floor = image[:, -6:]
    np.testing.assert_allclose(floor, L_ENV, rtol=1e-6)


@pytest.mark.parametrize("integrator", ['<integrator type="path"/>', '<integrator type="ao"/>', ""],
                         ids=["path without it", "ao without it", "none"])
def test_without_hide_emitters_it_is_black(mcval, tmp_path, integrator):
    assert (_mcval(mcval, _scene(tmp_path, integrator))[:, :8] == 0).all()


def test_mitsubas_mapping_and_an_engine_files_scene_keep_the_files_value(tmp_path):
    for integrator, expected in ((SHOWN, "false"), (NESTED, "false"), ('<integrator type="path"/>', "true")):
        root = ET.fromstring(mitsuba_xml(open(_scene(tmp_path, integrator)).read(), "ao"))
        (flag,) = [e.get("value") for e in root.find("integrator") if e.get("name") == "hide_emitters"]
        assert flag == expected
    text, _, _ = written_scene(_scene(tmp_path, SHOWN), {}, "my_ao", 4)
    integrator = ET.fromstring(text).find("integrator")
    assert integrator.get("type") == "my_ao" and integrator.find("boolean").get("value") == "false"
    text, _, _ = written_scene(_scene(tmp_path, '<integrator type="path"/>'), {}, "my_ao", 4)
    assert ET.fromstring(text).find("integrator").find("boolean") is None


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_mcval_and_mitsuba_agree_with_the_environment_shown(mcval, mitsuba, tmp_path, seed):
    scene = _scene(tmp_path, SHOWN)
    reference = mitsuba.render(scene, "ao", SPP, K, 100 + seed).batches
    assert np.allclose(reference[:, :8], L_ENV)
    assert compare_batches(_mcval(mcval, scene, seed), reference).passed


def test_a_hidden_environment_against_a_shown_one_fails(mcval, mitsuba, tmp_path):
    reference = mitsuba.render(_scene(tmp_path, SHOWN), "ao", SPP, K, 7).batches
    assert not compare_batches(_mcval(mcval, _scene(tmp_path, '<integrator type="path"/>')), reference).passed
