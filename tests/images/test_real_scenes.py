"""Real Mitsuba scenes (issue 11): the chosen integrator's needs are modelled, what cannot change its answer is
honoured or skipped with one note line, what would change it is an error naming file, line and why."""
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import OpenEXR
import pytest

ROOT = Path(__file__).resolve().parents[2]
RENDER = shutil.which("render") or str(ROOT / "build" / "render")
CORNELL = ROOT / "scenes" / "real" / "cornell_box.xml"

PLANE = """<scene version="3.0.0">
    <integrator type="{integrator}"/>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        {sensor_extra}
        <transform name="to_world"><lookat origin="0, 3, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="8"/><integer name="height" value="8"/>
            {film_extra}
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="100"/><rotate x="1" angle="-90"/></transform>
        {shape_extra}
    </shape>
    <emitter type="point"><point name="position" value="0, 2, 0"/></emitter>
    <emitter type="constant"/>
</scene>
"""


def scene(tmp_path, integrator="bdpt", sensor_extra="", film_extra="", shape_extra=""):
    path = tmp_path / "scene.xml"
    path.write_text(PLANE.format(integrator=integrator, sensor_extra=sensor_extra, film_extra=film_extra,
                                 shape_extra=shape_extra))
    return path


def run(*args):
    return subprocess.run([RENDER, *map(str, args)], capture_output=True, text=True)


def one_error(res, path, *words):
    assert res.returncode == 1
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert lines[0].startswith(f"error: {path}:"), lines[0]
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


def test_the_cornell_box_is_generated_by_its_script(tmp_path):
    text = CORNELL.read_text()
    assert "make_cornell_box.py" in text.splitlines()[0]
    script = ROOT / "scenes" / "real" / "make_cornell_box.py"
    copy = tmp_path / script.name
    shutil.copy(script, copy)
    subprocess.run([sys.executable, str(copy)], check=True, capture_output=True)
    assert (tmp_path / "cornell_box.xml").read_text() == text, "cornell_box.xml differs from its generator's output"


@pytest.mark.parametrize("integrator", ["normals", "ao"])
def test_cornell_box_renders_with_normals_and_ao(integrator, tmp_path):
    out = tmp_path / "out.exr"
    res = run(CORNELL, "--integrator", integrator, "--spp", 2, "-o", out, "-q")
    assert res.returncode == 0, res.stderr
    notes = res.stderr.strip().splitlines()
    assert len(notes) == 1 and notes[0].startswith("note: ") and '<emitter type="area">' in notes[0], res.stderr
    with OpenEXR.File(str(out)) as f:
        rgb = f.channels()["RGB"].pixels
        assert rgb.shape == (256, 256, 3) and np.all(np.isfinite(rgb)) and np.any(rgb != 0)
        assert f.header()["mcval.integrator"] == integrator


def test_cornell_box_with_simple_is_one_line_error(tmp_path):
    one_error(run(CORNELL, "--integrator", "simple", "-o", tmp_path / "o.exr", "-q"), CORNELL, "no point light")
    assert not (tmp_path / "o.exr").exists()


def test_the_files_own_path_integrator_renders_without_override(tmp_path):
    # Its own <integrator type="path"> with the file's max_depth, at a small size and budget.
    res = run(CORNELL, "-o", tmp_path / "o.exr", "-q", "--spp", "1", "-D", "res=16")
    assert res.returncode == 0, res.stderr


def test_python_api_override(tmp_path):
    import mcval_renderer
    out = mcval_renderer.render(str(CORNELL), spp=1, integrator="ao")
    assert out["mean"].shape == (256, 256, 3) and out["stats"]["integrator"] == "ao"
    with pytest.raises(ValueError, match="no point light"):
        mcval_renderer.render(str(CORNELL), spp=1, integrator="simple")


@pytest.mark.parametrize("integrator", ["normals", "simple", "ao"])
def test_focus_distance_and_film_formats_render_with_any_file_integrator(integrator, tmp_path):
    path = scene(tmp_path, sensor_extra='<float name="focus_distance" value="3"/>',
                 film_extra='<string name="pixel_format" value="rgb"/>'
                            '<string name="component_format" value="float32"/>'
                            '<string name="file_format" value="openexr"/>')
    res = run(path, "--integrator", integrator, "-o", tmp_path / "o.exr", "-q")
    assert res.returncode == 0 and res.stderr == "", res.stderr


def test_focus_distance_does_not_change_the_image(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    images = []
    for d, extra in ((a, ""), (b, '<float name="focus_distance" value="0.5"/>')):
        path = scene(d, sensor_extra=extra)
        assert run(path, "--integrator", "normals", "-o", d / "o.exr", "-q").returncode == 0
        with OpenEXR.File(str(d / "o.exr")) as f:
            images.append(f.channels()["RGB"].pixels.copy())
    assert np.array_equal(*images)


@pytest.mark.parametrize("fmt,dtype", [("float16", np.float16), ("float32", np.float32)])
def test_component_format_is_honoured(fmt, dtype, tmp_path):
    path = scene(tmp_path, film_extra=f'<string name="component_format" value="{fmt}"/>')
    assert run(path, "--integrator", "ao", "-o", tmp_path / "o.exr", "-q").returncode == 0
    with OpenEXR.File(str(tmp_path / "o.exr")) as f:
        pixels = f.channels()["RGB"].pixels
        assert pixels.dtype == dtype
    # The harness reads it through OpenImageIO: the same values, as float32.
    from harness.exr import read_layers
    layers, attributes = read_layers(tmp_path / "o.exr")
    assert layers["RGB"].dtype == np.float32 and np.array_equal(layers["RGB"], pixels.astype(np.float32))
    assert "mcval.renderSeconds" in attributes


def test_bad_component_format_is_an_error(tmp_path):
    path = scene(tmp_path, film_extra='<string name="component_format" value="uint8"/>')
    line = one_error(run(path, "--integrator", "ao", "-o", tmp_path / "o.exr", "-q"), path, "component_format")
    assert f"{path}:8:" in line  # the <film> element's line


def test_non_diffuse_bsdf_is_a_note_for_normals_and_ao_read_by_direct_and_path_and_an_error_for_simple(tmp_path):
    path = scene(tmp_path, shape_extra='<bsdf type="conductor"/>')
    for integrator in ("normals", "ao"):  # neither reads a material
        res = run(path, "--integrator", integrator, "-o", tmp_path / "o.exr", "-q")
        assert res.returncode == 0
        notes = res.stderr.strip().splitlines()
        assert len(notes) == 1 and notes[0].startswith("note: ") and "conductor" in notes[0]
    for integrator in ("direct", "path"):  # they read every BSDF of the BSDF matrix
        res = run(path, "--integrator", integrator, "-o", tmp_path / "o.exr", "-q")
        assert res.returncode == 0 and "conductor" not in res.stderr, res.stderr
    line = one_error(run(path, "--integrator", "simple", "-o", tmp_path / "o.exr", "-q"), path,
                     "conductor", "simple", "diffuse")
    assert f"{path}:15:" in line
    # A type no integrator models is an error for each that reads the material.
    path = scene(tmp_path, shape_extra='<bsdf type="principled"/>')
    for integrator in ("simple", "direct", "path"):
        line = one_error(run(path, "--integrator", integrator, "-o", tmp_path / "o.exr", "-q"), path,
                         "principled", integrator, "diffuse")
        assert f"{path}:15:" in line


def test_an_area_emitter_loads_where_the_integrator_ignores_it(tmp_path):
    """simple sees point lights only, ao no emitter: a file with an area emitter renders under both (harness
    drops it from Mitsuba's copy under simple)."""
    path = scene(tmp_path, shape_extra='<emitter type="area"><rgb name="radiance" value="1"/></emitter>')
    for integrator in ("simple", "ao"):
        assert run(path, "--integrator", integrator, "-o", tmp_path / "o.exr", "-q").returncode == 0


def test_unknown_file_integrator_without_override_names_file_and_line(tmp_path):
    path = scene(tmp_path)
    one_error(run(path, "-o", tmp_path / "o.exr", "-q"), path, ":2:", 'unsupported integrator type "bdpt"')


def test_the_written_cornell_box_is_mitsubas_own():
    """Mitsuba loads the written XML into the same shapes (bounding boxes) and emitter as mi.cornell_box()."""
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    mcval, theirs = mi.load_file(str(CORNELL)), mi.load_dict(mi.cornell_box())

    def boxes(s):
        return sorted((sh.id(), tuple(sh.bbox().min), tuple(sh.bbox().max)) for sh in s.shapes())

    a, b = boxes(mcval), boxes(theirs)
    assert [x[0] for x in a] == [x[0] for x in b]
    np.testing.assert_allclose(np.array([x[1] + x[2] for x in a]), np.array([x[1] + x[2] for x in b]), atol=1e-6)
    assert len(mcval.emitters()) == len(theirs.emitters()) == 1
    assert list(mcval.sensors()[0].film().size()) == list(theirs.sensors()[0].film().size())
    assert str(mcval.sensors()[0]) == str(theirs.sensors()[0])


def test_float16_holds_the_float32_image(tmp_path):
    images = []
    for fmt in ("float16", "float32"):
        d = tmp_path / fmt
        d.mkdir()
        path = scene(d, film_extra=f'<string name="component_format" value="{fmt}"/>')
        assert run(path, "--integrator", "ao", "--seed", 3, "-o", d / "o.exr", "-q").returncode == 0
        with OpenEXR.File(str(d / "o.exr")) as f:
            images.append(f.channels()["RGB"].pixels.astype(np.float32))
    np.testing.assert_allclose(images[0], images[1], rtol=1e-3, atol=1e-4)
