"""<shape type="sphere">: `render` draws the exact sphere with every integrator, and the same file
means the same sphere to Mitsuba 3 (centre, radius and to_world composed alike)."""
import shutil
import subprocess
from pathlib import Path

import numpy as np
import OpenEXR
import pytest

ROOT = Path(__file__).resolve().parents[2]
RENDER = shutil.which("render") or str(ROOT / "build" / "render")

# A unit sphere moved to (0, 1, 0) by center, then scaled by 2, turned and lifted by to_world:
# Mitsuba composes to_world * translate(center) * scale(radius), a sphere of radius 1 at (-2, 0, 1).
SCENE = """<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="-2, 1, 8" target="-2, 0, 1" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="32"/><integer name="height" value="32"/><rfilter type="box"/>
        </film>
    </sensor>
    <shape type="sphere">
        <point name="center" value="0, 1, 0"/>
        <float name="radius" value="0.5"/>
        <transform name="to_world">
            <scale value="2"/>
            <rotate z="1" angle="90"/>
            <translate value="0, 0, 1"/>
        </transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.35, 0.7"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/><translate value="0, -1, 0"/></transform>
    </shape>
    <emitter type="point">
        <point name="position" value="1, 5, 4"/>
        <rgb name="intensity" value="60, 60, 60"/>
    </emitter>
    <emitter type="constant"/>
</scene>
"""


@pytest.fixture()
def scene(tmp_path):
    path = tmp_path / "sphere.xml"
    path.write_text(SCENE)
    return path


@pytest.mark.parametrize("integrator", ["normals", "simple", "ao"])
def test_render_draws_the_sphere(scene, integrator, tmp_path):
    out = tmp_path / f"{integrator}.exr"
    res = subprocess.run([RENDER, str(scene), "--integrator", integrator, "-o", str(out), "-q"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    with OpenEXR.File(str(out)) as f:
        rgb = f.channels()["RGB"].pixels
    assert rgb.shape == (32, 32, 3)
    assert np.all(np.isfinite(rgb)) and np.any(rgb != 0)
    centre = rgb[15:17, 15:17].mean(axis=(0, 1))
    if integrator == "normals":
        # The camera looks at the sphere's centre: the normal there faces it, (0, 1, 7) normalised.
        assert np.allclose(centre, np.array([0.0, 1.0, 7.0]) / np.sqrt(50.0), atol=0.05)
    else:
        assert np.all(centre > 0)


def test_mitsuba_loads_the_same_sphere(scene):
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    loaded = mi.load_file(str(scene))
    spheres = [s for s in loaded.shapes() if min(s.bbox().extents()) > 0]  # the rectangle is flat
    assert len(spheres) == 1
    box = spheres[0].bbox()
    assert np.allclose(np.array(box.center()), [-2.0, 0.0, 1.0], atol=1e-5)
    assert np.allclose(np.array(box.extents()), [2.0, 2.0, 2.0], atol=1e-5)
