"""What the renderer does not model is refused by name, at its line, and only where the integrator would read it:
a textured reflectance (inline or by reference) under simple, a spot light's textured intensity, a projector."""
import subprocess

import pytest

from harness.engines.render_process import render_binary

SCENE = """<scene version="3.0.0">
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
  <emitter type="point"><point name="position" x="0" y="0" z="5"/></emitter>
  {extra}
  <shape type="sphere"><bsdf type="diffuse">{reflectance}</bsdf></shape>
</scene>
"""
CHECKER = '<texture type="checkerboard" id="checks"/>'


def run(tmp_path, integrator, extra="", reflectance=""):
    scene = tmp_path / "scene.xml"
    scene.write_text(SCENE.format(extra=extra, reflectance=reflectance))
    out = tmp_path / "out.exr"
    res = subprocess.run([str(render_binary()), str(scene), "--integrator", integrator, "-o", str(out), "-q"],
                         capture_output=True, text=True)
    return res, out, scene


@pytest.mark.parametrize("extra, reflectance, message", [
    ("", '<texture type="checkerboard" name="reflectance"/>', "given here as a checkerboard texture at line 5"),
    (CHECKER, '<ref id="checks" name="reflectance"/>', 'given here as a reference to "checks" (a texture) at line 5'),
])
def test_a_textured_reflectance_is_named_where_it_is_read(tmp_path, extra, reflectance, message):
    res, out, scene = run(tmp_path, "simple", extra, reflectance)
    assert res.returncode != 0 and not out.exists()
    assert f"{scene}:5:" in res.stderr and message in res.stderr, res.stderr
    res, out, _ = run(tmp_path, "normals", extra, reflectance)  # normals reads no reflectance
    assert res.returncode == 0 and out.exists(), res.stderr


def test_a_spot_lights_textured_intensity_is_named(tmp_path):
    """(Its projected image, `texture`, is read: tests/cpp/test_textures.cpp.)"""
    spot = '<emitter type="spot"><texture type="checkerboard" name="intensity"/></emitter>'
    res, out, scene = run(tmp_path, "direct", spot)
    assert res.returncode != 0 and not out.exists()
    assert f"{scene}:4:" in res.stderr and 'textured emission ("intensity")' in res.stderr, res.stderr
    res, out, _ = run(tmp_path, "simple", spot)  # simple reads point lights only: the spot is skipped
    assert res.returncode == 0 and "skipped" in res.stderr, res.stderr


def test_a_projector_is_named_by_its_type(tmp_path):
    res, out, scene = run(tmp_path, "direct", '<emitter type="projector"/>')
    assert res.returncode != 0 and not out.exists()
    assert f"{scene}:4:" in res.stderr and "lit by this projector emitter" in res.stderr, res.stderr
