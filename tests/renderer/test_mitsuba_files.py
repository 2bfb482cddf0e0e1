"""The `render` command on a scene file written as exporters and Mitsuba's own tutorials write them: what Mitsuba 3
loads and our integrators' answers do not depend on loads (a stratified sampler with a seed, an <integer> for a
float, a <ref> before its bsdf, a medium, an area emitter under simple, Mitsuba 0.5 names), and the image is the
crop window of the film, through a tent filter. Bad inputs fail with the file's line."""
import subprocess

import numpy as np
import OpenEXR
import pytest

from harness.engines.render_process import render_binary

EXPORTED = """<scene version="{version}">
  <default name="spp" value="4"/>
  <sensor type="perspective">
    <integer name="fov" value="45"/>
    <transform name="{to_world}"><lookat origin="0, 1, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <ref id="air"/>
    <sampler type="stratified"><integer name="sample_count" value="$spp"/><integer name="seed" value="3"/></sampler>
    <film type="hdrfilm">
      <integer name="width" value="32"/><integer name="height" value="24"/>
      <integer name="crop_offset_x" value="4"/><integer name="crop_offset_y" value="2"/>
      <integer name="crop_width" value="20"/><integer name="crop_height" value="10"/>
      <rfilter type="tent"><float name="radius" value="1.5"/></rfilter>
    </film>
  </sensor>
  <medium type="homogeneous" id="air"/>
  <shape type="sphere"><ref id="material"/><ref name="exterior" id="air"/></shape>
  <shape type="rectangle">
    <transform name="{to_world}"><scale value="4"/><rotate x="1" angle="-90"/><translate y="-1"/></transform>
    <bsdf type="twosided"><bsdf type="diffuse"><rgb name="{reflectance}" value="0.2, 0.4, 0.6"/></bsdf></bsdf>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter>
  </shape>
  <bsdf type="twosided" id="material"><bsdf type="diffuse"/></bsdf>
  <emitter type="point"><point name="position" value="1, 3, 2"/></emitter>
</scene>
"""
MODERN = {"version": "3.0.0", "to_world": "to_world", "reflectance": "reflectance"}
MITSUBA_05 = {"version": "0.5.0", "to_world": "toWorld", "reflectance": "diffuseReflectance"}


def run(scene, tmp_path, integrator):
    out = tmp_path / "out.exr"
    res = subprocess.run([str(render_binary()), str(scene), "--integrator", integrator, "-o", str(out), "-q"],
                         capture_output=True, text=True)
    return res, out


@pytest.mark.parametrize("names", [MODERN, MITSUBA_05], ids=["3.0", "0.5"])
@pytest.mark.parametrize("integrator", ["normals", "ao", "simple"])
def test_an_exported_file_renders_its_crop_window(tmp_path, names, integrator):
    scene = tmp_path / "exported.xml"
    scene.write_text(EXPORTED.format(**names))
    res, out = run(scene, tmp_path, integrator)
    assert res.returncode == 0, res.stderr
    with OpenEXR.File(str(out)) as f:
        rgb = f.channels()["RGB"].pixels
        assert f.header()["mcval.sampler"] == "sobol"
    assert rgb.shape == (10, 20, 3)
    assert np.all(np.isfinite(rgb)) and np.any(rgb != 0)
    if integrator != "normals":  # media and the area emitter are named as skipped
        assert "skipped, not used by the" in res.stderr and "<medium>" in res.stderr


@pytest.mark.parametrize("change, line, message", [
    (('<float name="radius" value="1.5"/>', '<float name="radius" value="40"/>'), 12, "radius must lie in"),
    (('name="crop_width" value="20"', 'name="crop_width" value="29"'), 11, "the crop window must lie within the film"),
    (('<ref id="material"/>', '<ref id="nothing"/>'), 16, 'no <bsdf id="nothing"> in the file'),
    (('type="stratified"', 'type="halton"'), 7, "unsupported sampler type"),
])
def test_what_cannot_load_names_its_line(tmp_path, change, line, message):
    scene = tmp_path / "bad.xml"
    scene.write_text(EXPORTED.format(**MODERN).replace(*change))
    res, out = run(scene, tmp_path, "ao")
    assert res.returncode != 0 and not out.exists()
    assert f"{scene}:{line}:" in res.stderr and message in res.stderr, res.stderr
