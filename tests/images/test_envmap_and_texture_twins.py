"""An environment map, textured reflectances and a mask through the image suite, on a scene of one's own
(--scene): a quad from an OBJ with texture coordinates under an 8-bit PNG, a checkerboard rectangle, a rectangle
cut into a checkerboard by a mask, and an OpenEXR sky with a bright sun seen directly and lighting them. Our direct and path pass against Mitsuba rendering it, and a renderer
that reads one of them wrong fails. The wrong readings are planted by handing our renderer the scene (or the mesh)
with that reading made, as a loader with the defect would see it:
- the sky turned half a turn about its vertical (longitude measured from the wrong side);
- the OBJ's texture coordinates not turned upside down (Mitsuba's v is 1 - the file's);
- the PNG taken as linear (its sRGB curve not undone);
- the mask's holes not read (every square opaque).
Each case at 32 pixels and its integrator's samples, seed 0."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import OpenImageIO as oiio
import pytest

from harness.engines.mcval import McvalEngine
from harness.images.run import run_images
from harness.images.suite import select_cases
from harness.images.user_scenes import prepare_scenes
from tests.images.test_material_twins import MisreadingEngine

SCENE = """<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="60"/>
    <transform name="to_world"><lookat origin="0, -3, 1.5" target="0, 0, 0.2" up="0, 0, 1"/></transform>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/></film>
  </sensor>
  <emitter type="envmap">
    <string name="filename" value="sky.exr"/>
    <transform name="to_world"><rotate x="1" angle="90"/></transform>
  </emitter>
  <shape type="obj">
    <string name="filename" value="quad.obj"/>
    <bsdf type="diffuse">
      <texture name="reflectance" type="bitmap"><string name="filename" value="stripes.png"/></texture>
    </bsdf>
  </shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.6"/><rotate x="1" angle="90"/><translate value="0.9, 0.3, 0.6"/></transform>
    <bsdf type="diffuse">
      <texture name="reflectance" type="checkerboard">
        <rgb name="color0" value="0.8, 0.3, 0.1"/><rgb name="color1" value="0.1, 0.4, 0.7"/>
        <transform name="to_uv"><scale value="3"/></transform>
      </texture>
    </bsdf>
  </shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate value="-0.8, -0.5, 0.5"/></transform>
    <bsdf type="mask">
      <texture name="opacity" type="checkerboard">
        <float name="color0" value="1"/><float name="color1" value="0"/>
        <transform name="to_uv"><scale value="2"/></transform>
      </texture>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.9, 0.9, 0.2"/></bsdf>
    </bsdf>
  </shape>
</scene>
"""

#: A floor quad of 4 x 4 at z = 0 whose (u, v) run 0..1 across it (v from the file, before Mitsuba's turn).
QUAD = "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"


def _write_image(path: Path, pixels: np.ndarray, kind: str) -> None:
    out = oiio.ImageOutput.create(str(path))
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], pixels.shape[2], kind)
    assert out.open(str(path), spec) and out.write_image(pixels) and out.close()


@pytest.fixture(scope="module")
def scene(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("envmap_textures")
    (folder / "scene.xml").write_text(SCENE)
    (folder / "quad.obj").write_text(QUAD)
    flipped = "".join(f"vt {line.split()[1]} {1 - float(line.split()[2]):g}\n" if line.startswith("vt") else line + "\n"
                      for line in QUAD.splitlines())
    (folder / "quad_flipped.obj").write_text(flipped)
    # Stripes that differ top to bottom, mid-grey values where sRGB and linear differ most.
    stripes = np.zeros((8, 8, 3), np.uint8)
    for y in range(8):
        stripes[y] = [40 + 25 * y, 200 - 20 * y, 128]
    stripes[:, :2] = [230, 230, 230]
    _write_image(folder / "stripes.png", stripes, "uint8")
    # A dim blue sky with a warm sun off the camera's side, and a dark ground.
    sky = np.zeros((16, 32, 3), np.float32)
    for y in range(16):
        sky[y] = [0.3, 0.45, 0.8] if y < 8 else [0.05, 0.04, 0.03]
    sky[3, 5] = [60.0, 50.0, 30.0]
    _write_image(folder / "sky.exr", sky, "float")
    return folder / "scene.xml"


def _case(scene: Path, tmp_path: Path, integrator: str):
    user = prepare_scenes([scene], tmp_path / "cache", 32)
    (case,) = select_cases([f"scene:{integrator}"], user=user)
    return case


@pytest.mark.parametrize("integrator", ["direct", "path"])
def test_our_renderer_passes_on_the_sky_and_the_textures(scene, tmp_path, mitsuba, integrator):
    (result,), _ = run_images([_case(scene, tmp_path, integrator)], McvalEngine(), mitsuba)
    assert result.verdict == "PASS", result.why


#: (pattern, replacement) in the prepared copy our renderer is given.
DEFECTS = {
    "sky_turned": (r'<rotate x="1" angle="90"\s*/>\s*</transform>\s*</emitter>',
                   '<rotate x="1" angle="90"/><rotate z="1" angle="180"/></transform></emitter>'),
    "v_not_flipped": (r"quad\.obj", "quad_flipped.obj"),
    "srgb_ignored": (r'(<string name="filename" value="[^"]*stripes\.png"\s*/>)',
                     r'\1<boolean name="raw" value="true"/>'),
    "mask_opaque": (r'<float name="color1" value="0"\s*/>', '<float name="color1" value="1"/>'),
}


@pytest.mark.parametrize("defect", sorted(DEFECTS))
def test_a_sky_or_texture_read_wrong_fails_against_mitsuba(scene, tmp_path, mitsuba, defect):
    (result,), _ = run_images([_case(scene, tmp_path, "direct")], MisreadingEngine(*DEFECTS[defect], tmp_path),
                              mitsuba)
    assert result.verdict == "FAIL"
    assert not result.comparisons["mitsuba"].passed
