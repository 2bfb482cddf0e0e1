"""The prepared copy of a --scene file: malformed sizes and defaults refused with FILE:LINE, the run's resolution
given to film-less files and crop windows, Mitsuba's own camera written out for a file without a sensor, and a
map from every line of the copy to the line of the file it came from."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness.engines.nori.lined_xml import SceneXmlError
from harness.images.scene_copy import MITSUBA_FILM, default_sensor, prepare_mitsuba_file
from harness.images.suite import SCENES_DIR

PLANE = (SCENES_DIR / "plane_point.xml").read_text()
WIDTH = '<integer name="width" value="$res"/>'


def _prepare(tmp_path, text, resolution=64, bounds=None):
    path = tmp_path / "s.xml"
    path.write_text(text)
    return prepare_mitsuba_file(text, path, resolution, lambda _: bounds), path


def _film(text: str) -> dict[str, str]:
    film = next(ET.fromstring(text).iter("film"))
    return {e.get("name"): e.get("value") for e in film if e.get("name")}


@pytest.mark.parametrize("old, new", [
    ('<default name="res" value="128"/>', '<default name="res"/>'),
    ('<default name="res" value="128"/>', '<default value="128"/>'),
    (WIDTH, '<integer name="width" value="abc"/>'),
    (WIDTH, '<integer name="width" value="1.5"/>'),
    (WIDTH, '<integer name="width" value=""/>'),
    (WIDTH, '<integer name="width" value="-5"/>'),
    (WIDTH, '<integer name="width" value="0"/>'),
    (WIDTH, '<integer name="width" value="$nothing"/>'),
    ('<integer name="height" value="$res"/>', '<integer name="height" value="1e3"/>'),
    ('<integer name="height" value="$res"/>', f'<integer name="height" value="{10**400}"/>'),
    ('<rfilter type="box"/>', '<rfilter type="box"/><integer name="crop_width" value="-1"/>'),
])
def test_a_malformed_size_or_default_is_refused_with_its_line(tmp_path, old, new):
    text = PLANE.replace(old, new)
    with pytest.raises(SceneXmlError) as refused:
        _prepare(tmp_path, text)
    line = text[:text.index(new)].count("\n") + 1
    assert str(refused.value).startswith(f"{tmp_path / 's.xml'}:{line}: <"), str(refused.value)
    assert "\n" not in str(refused.value)


@pytest.mark.parametrize("width, height", [(10**18, 64), (1, 1), (16384, 9), (3, 48)])
def test_any_whole_number_of_pixels_is_scaled_to_the_run(tmp_path, width, height):
    text = PLANE.replace(WIDTH, f'<integer name="width" value="{width}"/>') \
        .replace('<integer name="height" value="$res"/>', f'<integer name="height" value="{height}"/>')
    prepared, _ = _prepare(tmp_path, text, 32)
    film = _film(prepared.text)
    assert film["width"] == "$res"
    assert film["height"] == ("$res" if width == height else str(max(1, round(32 * height / width))))


def test_a_film_far_taller_than_wide_is_refused(tmp_path):
    text = PLANE.replace(WIDTH, '<integer name="width" value="3"/>') \
        .replace('<integer name="height" value="$res"/>', '<integer name="height" value="1000000"/>')
    with pytest.raises(SceneXmlError, match=r"s.xml:41: <film .*32 x 10666667 pixels"):
        _prepare(tmp_path, text, 32)


def test_a_crop_window_is_scaled_with_the_film(tmp_path):
    crop = "".join(f'<integer name="{k}" value="{v}"/>' for k, v in
                   (("crop_offset_x", 64), ("crop_offset_y", 32), ("crop_width", 128), ("crop_height", 48)))
    text = PLANE.replace('<rfilter type="box"/>', '<rfilter type="box"/>' + crop) \
        .replace(WIDTH, '<integer name="width" value="256"/>') \
        .replace('<integer name="height" value="$res"/>', '<integer name="height" value="128"/>')
    prepared, _ = _prepare(tmp_path, text, 64)
    assert _film(prepared.text) == {"width": "$res", "height": "32", "crop_offset_x": "16", "crop_offset_y": "8",
                                    "crop_width": "32", "crop_height": "12"}


def test_a_film_less_sensor_gets_mitsubas_default_film_at_the_runs_resolution(tmp_path):
    text = PLANE[:PLANE.index("<film")] + PLANE[PLANE.index("</film>") + len("</film>"):]
    prepared, _ = _prepare(tmp_path, text, 64)
    assert _film(prepared.text) == {"width": "$res", "height": str(round(64 * MITSUBA_FILM[1] / MITSUBA_FILM[0]))}
    root = ET.fromstring(prepared.text)
    assert [e.get("value") for e in root if e.tag == "default" and e.get("name") == "res"] == ["64"]


def test_every_line_of_the_copy_maps_to_the_line_it_came_from(tmp_path):
    prepared, _ = _prepare(tmp_path, PLANE)
    source = PLANE.splitlines()
    for k, line in enumerate(prepared.text.splitlines(), start=1):
        e = ET.fromstring(line if line.strip().endswith("/>") else line.replace(">", "/>", 1)) \
            if line.strip().startswith("<") and not line.strip().startswith("</") else None
        if e is None or e.get("name") == "res" and e.tag == "default" or e.get("name") in ("width", "height"):
            continue  # end tags, and what the copy added
        original = source[prepared.source_lines[k] - 1]
        assert f"<{e.tag}" in original and all(f'"{v}"' in original for v in e.attrib.values()), (line, original)


SENSORLESS = """<scene version="3.0.0">
    <shape type="sphere"><point name="center" x="1" y="2" z="3"/><float name="radius" value="0.5"/></shape>
    <shape type="rectangle">
        <transform name="to_world"><scale x="2" y="1"/><translate z="-1"/></transform>
    </shape>
</scene>
"""


@pytest.mark.mitsuba
def test_a_sensorless_file_gets_the_camera_mitsuba_gave_it_before_3(tmp_path):
    """Mitsuba 3.0.0 and later make no camera (scene.sensors() is empty); the one written out is, in Mitsuba,
    the camera its scene.cpp made until then: at (center x, center y, min z - d) looking along +z, d = the
    largest extent over 2 tan(22.5 degrees), 45 degrees wide, clipped at d / 100 and 5 extents + d."""
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    from harness.engines.mitsuba_bounds import scene_bounds

    path = tmp_path / "s.xml"
    path.write_text(SENSORLESS)
    notes = []
    prepared = prepare_mitsuba_file(SENSORLESS, path, 48, lambda text: scene_bounds(text, "scalar_rgb"), notes=notes)
    assert len(notes) == 1 and notes[0].startswith(f"{path}: no <sensor>")
    assert mi.load_string(SENSORLESS).sensors() == []
    scene = mi.load_string(prepared.text)
    (sensor,) = scene.sensors()
    box = scene.bbox()
    extent = max(box.max - box.min)
    d = extent / (2 * math.tan(math.radians(22.5)))
    origin = sensor.world_transform() @ mi.ScalarPoint3f(0, 0, 0)
    forward = sensor.world_transform() @ mi.ScalarVector3f(0, 0, 1)
    assert np.allclose(origin, [(box.min[0] + box.max[0]) / 2, (box.min[1] + box.max[1]) / 2, box.min[2] - d])
    assert np.allclose(forward, [0, 0, 1])
    assert math.isclose(float(mi.traverse(sensor)["x_fov"]), 45, rel_tol=1e-6)
    assert math.isclose(sensor.near_clip(), d / 100, rel_tol=1e-5)
    assert math.isclose(sensor.far_clip(), extent * 5 + d, rel_tol=1e-5)
    assert tuple(sensor.film().size()) == (48, 36)


def test_a_scene_without_shapes_gets_the_camera_at_the_origin():
    sensor = default_sensor(None, 32)
    assert sensor.find("transform") is None and sensor.find("float").get("value") == "45.0"


@pytest.mark.mitsuba
def test_mitsubas_error_on_a_sensorless_file_names_the_files_line(tmp_path):
    pytest.importorskip("mitsuba")
    from harness.engines.mitsuba_bounds import scene_bounds

    text = SENSORLESS.replace('<float name="radius" value="0.5"/>', '<float name="radius" value="0.5"/>\n\n<foo/>')
    path = tmp_path / "s.xml"
    with pytest.raises(SceneXmlError, match=rf"in {path}:4: .*<foo>"):
        prepare_mitsuba_file(text, path, 48, lambda t: scene_bounds(t, "scalar_rgb"))


@pytest.mark.mitsuba
def test_both_engines_render_a_sensorless_file_from_the_same_camera(tmp_path):
    from harness.engines.mitsuba import MitsubaEngine
    from harness.engines.mcval import McvalEngine
    from harness.images.case_renders import CaseRenders
    from harness.images.case_task import CaseJob, run_case_job
    from harness.images.suite import select_cases
    from harness.images.user_scenes import prepare_scenes

    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "bare.xml").write_text(SENSORLESS)
    (scene,) = prepare_scenes([tmp_path / "in"], tmp_path / "cache", 32)
    assert not scene.problem and len(scene.notes) == 1
    (case,) = select_cases(["bare:normals"], user=[scene])
    result, _ = run_case_job(CaseJob(case=case, seed=1, alpha=0.01, run_seed=0, closed_form=False,
                                          renders=CaseRenders(McvalEngine(), MitsubaEngine())))
    assert result.error is None and result.passed, result.error
    assert result.tested.mean.shape == (24, 32, 3) and (abs(result.tested.mean).sum(axis=-1) > 0).mean() > 0.1
