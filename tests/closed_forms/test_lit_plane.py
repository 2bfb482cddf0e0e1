"""A plane under one area light: the scenes are read as "lit_plane" with the light the file describes, the
scenes the closed form does not model are refused, and the analytic engine renders its image for an entry that
names the kind."""
from pathlib import Path

import numpy as np
import pytest

from harness.closed_forms import lit_plane
from harness.closed_forms.area_lights import DiskLight, PolygonLight, SphereLight
from harness.closed_forms.plane_scene import NotAnalytic, load_plane_scene
from harness.integrators.entry import AnalyticForm, IntegratorEntry
from tests.helpers import light_quadrature as quad

SCENES = Path(__file__).resolve().parents[2] / "scenes"
LIT = ("plane_rect_light", "plane_disk_light", "plane_sphere_light")
UP = np.array([0.0, 1.0, 0.0])


def _load(name: str):
    return load_plane_scene(SCENES / f"{name}.xml")


@pytest.mark.parametrize("name", LIT)
def test_the_lit_scenes_are_read_as_lit_planes(name):
    scene = _load(name)
    assert scene.kind == "lit_plane" and len(scene.area_lights) == 1 and scene.sphere is None
    assert np.allclose(scene.reflectance, 0.5)


@pytest.mark.parametrize("name, kind", [("plane_point", "plane"), ("plane_ao", "plane"),
                                        ("sphere_floor_unit", "sphere_floor")])
def test_the_other_analytic_scenes_keep_their_kind(name, kind):
    scene = _load(name)
    assert scene.kind == kind and scene.area_lights == ()


def test_the_rectangle_light_is_where_its_transform_puts_it():
    """Its corners worked out by hand from the file's steps (scale 0.5 x 0.3, turned down, tilted by 20 degrees
    about z, turned by 30 about y, raised by 2), counter-clockwise about its emitting normal."""
    light = _load("plane_rect_light").area_lights[0]
    assert isinstance(light, PolygonLight) and np.allclose(light.radiance, [6, 5, 4])
    t, y = np.radians(20), np.radians(30)
    tilt = np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
    turn = np.array([[np.cos(y), 0, np.sin(y)], [0, 1, 0], [-np.sin(y), 0, np.cos(y)]])
    corners = {tuple(np.round(turn @ tilt @ [x, 0, z] + [0, 2, 0], 9)) for x in (-0.5, 0.5) for z in (-0.3, 0.3)}
    assert {tuple(np.round(v, 9)) for v in light.vertices} == corners
    assert np.allclose(light.normal, turn @ tilt @ -UP)
    v = light.vertices
    assert np.cross(v[1] - v[0], v[2] - v[0]) @ light.normal > 0


def test_the_disk_and_sphere_lights_are_where_the_files_put_them():
    disk = _load("plane_disk_light").area_lights[0]
    assert isinstance(disk, DiskLight) and np.allclose(disk.center, [0, 2, -0.5]) and np.isclose(disk.radius, 0.5)
    assert np.allclose(disk.normal, -UP) and np.allclose(disk.radiance, 5)
    sphere = _load("plane_sphere_light").area_lights[0]
    assert isinstance(sphere, SphereLight) and np.allclose(sphere.center, [0, 2, -0.5])
    assert np.isclose(sphere.radius, 0.5) and np.allclose(sphere.radiance, [3, 4, 5])


def test_a_floor_point_is_rho_over_pi_times_the_irradiance():
    """Against quadrature over the rectangle as the file describes it, at a point under the light and one aside."""
    scene = _load("plane_rect_light")
    v = scene.area_lights[0].vertices
    for p in (np.array([0.1, 0, 0.2]), np.array([-2.0, 0, 3.0])):
        expected = 0.5 / np.pi * np.array([6, 5, 4]) * quad.rectangle(v[0], v[1] - v[0], v[3] - v[0], p, UP)
        assert np.allclose(lit_plane.radiance(scene, p[None], UP)[0], expected, rtol=1e-9)


def _edited(tmp_path, name: str, old: str, new: str) -> Path:
    text = (SCENES / f"{name}.xml").read_text()
    assert text.count(old) == 1, old
    path = tmp_path / f"{name}.xml"
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("name, old, new, why", [
    ("plane_disk_light", '<translate x="0" y="2" z="-0.5"/>', '<translate x="0" y="1.1" z="-0.5"/>', "camera could see"),
    ("plane_sphere_light", 'value="0, 2, -0.5"', 'value="0, 0.3, -0.5"', "below the floor's horizon"),
    ("plane_disk_light", '<rotate x="1" angle="90"/>', '<rotate x="1" angle="80"/>', "not parallel"),
    ("plane_disk_light", '<scale value="0.5"/>', '<scale x="0.5" y="0.3" z="1"/>', "ellipse"),
    ("plane_rect_light", 'origin="0, 1.2, 2.4"', 'origin="0, 1.9, 2.4"', "camera could see"),
    ("plane_rect_light", 'target="0, 0, 0"', 'target="0, 1.0, 0"', "every camera ray go down"),
    ("plane_sphere_light", "</scene>", '<emitter type="point"><point name="position" value="0, 3, 0"/></emitter></scene>',
     "beside other emitters"),
    ("plane_sphere_light", "</scene>", '<shape type="sphere"><point name="center" value="3, 2, 0"/>'
     '<emitter type="area"><rgb name="radiance" value="1"/></emitter></shape></scene>', "2 area lights"),
    ("plane_sphere_light", '<shape type="sphere">', '<shape type="cube">', "an emitting cube"),
])
def test_scenes_the_closed_form_does_not_model_are_refused(tmp_path, name, old, new, why):
    assert _load(name).kind == "lit_plane"  # the scene as it is, then the edit that takes it out of the model
    with pytest.raises(NotAnalytic, match=why):
        load_plane_scene(_edited(tmp_path, name, old, new))


def test_the_analytic_engine_renders_a_lit_plane_for_an_entry_that_names_it(monkeypatch):
    """The way an integrator's entry takes this closed form: AnalyticForm(..., scenes=("lit_plane",))."""
    import harness.engines.analytic as analytic

    form = AnalyticForm("rho / pi * E", lit_plane.radiance, scenes=("lit_plane",))
    probe = IntegratorEntry(name="lit", tested_spp=1, reference_spp=1, emitters=("area",), analytic=form)
    monkeypatch.setattr(analytic, "entry", lambda name: probe)
    path = str(SCENES / "plane_disk_light.xml")
    assert analytic.AnalyticEngine.supports(path, {"res": "16"}, "lit")
    image = analytic.AnalyticEngine().render(path, "lit", 16, 1, 0, {"res": "16"}).batches[0]
    assert image.shape == (16, 16, 3) and np.all(np.isfinite(image)) and image.min() > 0
    # The brightest floor point is under the disk's centre: rho / pi * pi L sin^2(alpha).
    assert image.max() <= 0.5 * 5 * 0.25 / (0.25 + 4) * (1 + 1e-6) and image.max() > 0.9 * 0.5 * 5 * 0.25 / 4.25
    monkeypatch.setattr(analytic, "entry", lambda name: IntegratorEntry(
        name="flat", tested_spp=1, reference_spp=1, emitters=("area",),
        analytic=AnalyticForm("a plane's", lit_plane.radiance, scenes=("plane",))))
    assert not analytic.AnalyticEngine.supports(path, {"res": "16"}, "flat")


def _rewritten_radiance(tmp_path, name: str, kind: str, value, points: np.ndarray) -> np.ndarray:
    """The closed form of the scene rewritten by an invariance, at the images of `points` under its matrix."""
    from harness.invariance.rewrite import rewrite, step_matrix

    path = rewrite(SCENES / f"{name}.xml", tmp_path / f"{name}-{kind}.xml", kind, value)
    scene = load_plane_scene(path)
    m = step_matrix(kind, value) if kind in ("scale", "rotate", "translate") else np.eye(4)
    moved = points @ m[:3, :3].T + m[:3, 3]
    normal = m[:3, :3] @ UP
    return lit_plane.radiance(scene, moved, normal / np.linalg.norm(normal))


INVARIANCE_STEPS = [("scale", 1e-3), ("scale", 1e3), ("rotate", ((0.3, 1.0, 0.2), 37.0)),
                    ("translate", (10.0, -20.0, 30.0))]


@pytest.mark.parametrize("name", LIT)
@pytest.mark.parametrize("kind, value", INVARIANCE_STEPS)
def test_scale_rotation_and_translation_leave_a_lit_plane_unchanged(tmp_path, name, kind, value):
    """The invariances' rewrites move each area light with its shape, and an area light's radiance needs no
    factor under scale (the solid angle it subtends is unchanged), unlike a point light's intensity."""
    points = np.array([[0.0, 0, 0], [0.4, 0, -0.7], [-3.0, 0, 2.0], [6.0, 0, -9.0]])
    base = lit_plane.radiance(_load(name), points, UP)
    assert np.allclose(_rewritten_radiance(tmp_path, name, kind, value, points), base, rtol=1e-9)


@pytest.mark.parametrize("name", LIT)
def test_the_light_rewrite_scales_the_area_lights_radiance(tmp_path, name):
    points = np.array([[0.0, 0, 0], [-3.0, 0, 2.0]])
    base = lit_plane.radiance(_load(name), points, UP)
    assert np.allclose(_rewritten_radiance(tmp_path, name, "light", 2.0, points), 2 * base, rtol=1e-12)


def test_an_area_light_scaled_as_a_point_light_is_rejected(tmp_path):
    """Planted twin: radiance times s^2 under scale (as a point light's intensity) breaks the scale invariance."""
    from harness.invariance.rewrite import rewrite

    scaled = rewrite(SCENES / "plane_disk_light.xml", tmp_path / "scaled.xml", "scale", 1e3)
    wrong = rewrite(scaled, tmp_path / "wrong.xml", "light", 1e6)
    points = np.array([[0.0, 0, -0.5], [2.0, 0, 1.0]])
    base = lit_plane.radiance(_load("plane_disk_light"), points, UP)
    assert not np.allclose(lit_plane.radiance(load_plane_scene(wrong), 1e3 * points, UP), base, rtol=1e-3)
