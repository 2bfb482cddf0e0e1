"""The furnace: scenes/furnace.xml is read as one, its closed forms are the sums of the bounces each integrator
follows, every scene the closed form does not hold for is refused, and the analytic engine renders its one value
for the integrators that have it (path, direct) and for no other."""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from harness.closed_forms.furnace import direct_radiance, is_furnace, load_furnace, path_radiance
from harness.closed_forms.plane_scene import NotAnalytic
from harness.engines.analytic import AnalyticEngine
from harness.integrators import entry

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "furnace.xml"
ALBEDO = np.array([0.8, 0.6, 0.4])


def _variant(tmp_path: Path, *replacements: tuple[str, str]) -> Path:
    """A copy of the furnace with each (pattern, replacement) applied once (each must match)."""
    text = SCENE.read_text()
    for pattern, new in replacements:
        text, n = re.subn(pattern, new, text, count=1)
        assert n == 1, pattern
    out = tmp_path / "variant.xml"
    out.write_text(text)
    return out


def test_the_scene_is_read_as_a_furnace():
    f = load_furnace(SCENE)
    assert f.kind == "furnace" and (f.width, f.height) == (64, 64)
    assert np.allclose(f.albedo, ALBEDO) and np.allclose(f.radiance, 1)
    assert f.integrator == "path" and f.integer_parameters == {"max_depth": 8, "rr_depth": 5}
    assert load_furnace(SCENE, {"res": "32"}).width == 32


def test_direct_sees_the_emission_and_its_first_reflection():
    assert np.allclose(direct_radiance(load_furnace(SCENE)), 1 + ALBEDO)


@pytest.mark.parametrize("depth, terms", [(0, 0), (1, 1), (2, 2), (3, 3), (8, 8)])
def test_path_sums_one_term_a_vertex(tmp_path, depth, terms):
    scene = _variant(tmp_path, (r'name="max_depth" value="8"', f'name="max_depth" value="{depth}"'))
    assert np.allclose(path_radiance(load_furnace(scene)), sum(ALBEDO ** k for k in range(terms)) + 0 * ALBEDO)


def test_path_without_a_limit_is_the_geometric_series(tmp_path):
    scene = _variant(tmp_path, (r'name="max_depth" value="8"', 'name="max_depth" value="-1"'))
    assert np.allclose(path_radiance(load_furnace(scene)), 1 / (1 - ALBEDO))
    # Another integrator's max_depth is not path's: Mitsuba's default (-1) holds.
    other = _variant(tmp_path, (r'<integrator type="path">', '<integrator type="direct">'))
    assert np.allclose(path_radiance(load_furnace(other)), 1 / (1 - ALBEDO))


def test_a_furnace_that_reflects_everything_has_no_limit(tmp_path):
    scene = _variant(tmp_path, (r'name="max_depth" value="8"', 'name="max_depth" value="-1"'),
                     (r'value="0.8, 0.6, 0.4"', 'value="1, 0.6, 0.4"'))
    with pytest.raises(NotAnalytic, match="without end"):
        path_radiance(load_furnace(scene))
    assert not AnalyticEngine.supports(str(scene), None, "path")
    assert AnalyticEngine.supports(str(scene), None, "direct")


def test_an_emitting_sphere_without_a_bsdf_is_black_inside(tmp_path):
    scene = _variant(tmp_path, (r'<bsdf type="diffuse">\s*<rgb name="reflectance" value="[^"]*"/>\s*</bsdf>', ""))
    assert np.allclose(direct_radiance(load_furnace(scene)), 1)


@pytest.mark.parametrize("replacement, why", [
    ((r'<boolean name="flip_normals" value="true"/>', ""), "flip_normals"),
    ((r'</scene>', '<shape type="sphere"><float name="radius" value="0.1"/></shape></scene>'), "no other shape"),
    ((r'</scene>', '<emitter type="point"><point name="position" value="0, 0, 0"/></emitter></scene>'),
     "only light"),
    ((r'<emitter type="area">', '<emitter type="spot">'), "only light"),
    ((r'<integer name="max_depth"', '<boolean name="hide_emitters" value="true"/><integer name="max_depth"'),
     "hidden emitters"),
    ((r'origin="0.3, -0.2, 0.1"', 'origin="0.3, -0.2, 2"'), "inside the sphere"),
    ((r'origin="0.3, -0.2, 0.1"', 'origin="0, 0, 0.995"'), "near clip"),
    ((r'<float name="fov" value="60"/>', '<float name="fov" value="60"/><float name="far_clip" value="1.5"/>'),
     "far"),
    ((r'<sensor type="perspective">', '<sensor type="orthographic">'), "perspective"),
    ((r'<rfilter type="box"/>', '<rfilter type="box"/><integer name="crop_width" value="8"/>'), "crop_width"),
    ((r'<bsdf type="diffuse">\s*<rgb name="reflectance" value="[^"]*"/>\s*</bsdf>', '<ref id="x"/>'), "KeyError"),
    ((r'<scene version="3.0.0">', '<scene version="3.0.0"><shape type="rectangle"/>'), "no other shape"),
])
def test_what_is_no_furnace_is_refused(tmp_path, replacement, why):
    scene = _variant(tmp_path, replacement)
    with pytest.raises(NotAnalytic, match=why):
        load_furnace(scene)
    assert not AnalyticEngine.supports(str(scene), None, "path")


@pytest.mark.parametrize("integrator, value", [("path", sum(ALBEDO ** k for k in range(8))), ("direct", 1 + ALBEDO)])
def test_the_analytic_engine_renders_the_one_value(integrator, value):
    result = AnalyticEngine().render(str(SCENE), integrator, 4, 3, seed=0, params={"res": "16"})
    assert result.batches.shape == (3, 16, 16, 3)
    assert np.allclose(result.batches, value.astype(np.float32), rtol=1e-6)


@pytest.mark.parametrize("integrator", ["normals", "ao", "simple"])
def test_integrators_without_a_furnace_form_get_none(integrator):
    assert not AnalyticEngine.supports(str(SCENE), None, integrator)


def test_ao_is_not_applicable_in_a_furnace_only():
    assert "furnace" in entry("ao").not_applicable(SCENE)
    assert entry("ao").not_applicable(SCENE.with_name("cornell.xml")) is None
    assert is_furnace(ET.parse(SCENE).getroot())
    assert not is_furnace(ET.parse(SCENE.with_name("sphere_floor_unit.xml")).getroot())


def test_a_broken_file_is_no_furnace_and_no_error(tmp_path):
    """A file that is not XML: NotAnalytic, as the plane scenes' reader says, so that supports() answers False."""
    broken = tmp_path / "broken.xml"
    broken.write_text('<scene version="3.0.0"><shape')
    with pytest.raises(NotAnalytic, match="ParseError"):
        load_furnace(broken)
    assert not AnalyticEngine.supports(str(broken), None, "path")
