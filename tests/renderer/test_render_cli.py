"""The `render` command and the Python module's render(): valid EXRs, clear errors, nothing half written."""
import shutil
import subprocess
from pathlib import Path

import numpy as np
import OpenEXR
import pytest

from tests.helpers.registered_integrators import PRODUCT, name_list

ROOT = Path(__file__).resolve().parents[2]
SCENES = sorted(p for p in (ROOT / "scenes").glob("*.xml") if not p.name.startswith("."))
RENDER = shutil.which("render") or str(ROOT / "build" / "render")


def run(*args, cwd=None):
    return subprocess.run([RENDER, *map(str, args)], capture_output=True, text=True, cwd=cwd)


@pytest.mark.parametrize("integrator", PRODUCT)
@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.stem)
def test_every_scene_and_integrator_writes_a_valid_exr(scene, integrator, tmp_path):
    from harness.integrators import entry

    out = tmp_path / "out.exr"
    res = run(scene, "--integrator", integrator, "--spp", 2, "-D", "res=24", "-o", out, "-q")
    # The harness never runs a case that is not applicable. Without a point light the renderer refuses simple
    # with its line; an enclosed camera (ao in the furnace) sees black, which the renderer renders.
    if entry(integrator).not_applicable(scene) == "no point light":
        assert res.returncode == 1 and f"{scene}:" in res.stderr and "no point light" in res.stderr, res.stderr
        return
    assert res.returncode == 0, res.stderr
    with OpenEXR.File(str(out)) as f:
        layers = f.channels()
        assert {"RGB", "variance"} <= set(layers)
        rgb = layers["RGB"].pixels
        assert rgb.shape == (24, 24, 3) and rgb.dtype == np.float32
        # Not black, but where the harness does not run the case (ao in the furnace).
        assert np.all(np.isfinite(rgb)) and (np.any(rgb != 0) or entry(integrator).not_applicable(scene))
        header = f.header()
        assert header["mcval.integrator"] == integrator
        assert int(header["mcval.cameraRays"]) == 24 * 24 * 2
        assert float(np.ravel(header["mcval.renderSeconds"])[0]) > 0


def test_batches_are_separate_layers(tmp_path):
    out = tmp_path / "b.exr"
    assert run(SCENES[0], "--spp", 1, "--batches", 3, "-D", "res=16", "-o", out, "-q").returncode == 0
    with OpenEXR.File(str(out)) as f:
        layers = f.channels()
        batches = np.stack([layers[f"batch{k}"].pixels for k in range(3)])
        assert np.allclose(layers["RGB"].pixels, batches.mean(axis=0), rtol=1e-5, atol=1e-7)


def test_a_bad_scene_fails_with_file_and_line_and_writes_nothing(tmp_path):
    scene = tmp_path / "bad.xml"
    scene.write_text('<scene version="3.0.0">\n  <sensor type="perspective"><float name="fov" value="4O"/>'
                     "</sensor>\n</scene>\n")
    out = tmp_path / "bad.exr"
    res = run(scene, "-o", out)
    assert res.returncode != 0
    assert f"{scene}:2:" in res.stderr and 'expected a number, got "4O"' in res.stderr
    assert list(tmp_path.iterdir()) == [scene]


def test_unknown_integrator_is_rejected_by_the_command_line(tmp_path):
    res = run(SCENES[0], "--integrator", "bdpt", "-o", tmp_path / "x.exr")
    assert res.returncode != 0 and "bdpt" in res.stderr
    assert not (tmp_path / "x.exr").exists()


def test_help_answers():
    res = run("--help")
    assert res.returncode == 0 and "--batches" in res.stdout and "--integrator" in res.stdout


def test_python_module_renders_numpy_arrays():
    import mcval_renderer
    out = mcval_renderer.render(str(SCENES[0]), spp=2, batches=2, integrator="ao", params={"res": "16"})
    assert out["mean"].shape == (16, 16, 3)
    assert out["batches"].shape == (2, 16, 16, 3)
    assert np.allclose(out["mean"], out["batches"].mean(axis=0), rtol=1e-5, atol=1e-7)
    assert out["stats"]["shadow_rays"] > 0
    with pytest.raises(ValueError, match=f"expected {name_list(PRODUCT)}"):
        mcval_renderer.render(str(SCENES[0]), integrator="bdpt")


@pytest.mark.parametrize("kind", ["fifo", "folder", "device", "missing_folder"])
def test_the_output_is_only_ever_a_regular_file(tmp_path, kind):
    """-o never renames over a FIFO, a folder or a device, and no temporary file is left."""
    import os
    target = {"fifo": tmp_path / "out.exr", "folder": tmp_path / "out.exr", "device": Path("/dev/null"),
              "missing_folder": tmp_path / "nowhere" / "out.exr"}[kind]
    if kind == "fifo":
        os.mkfifo(target)
    elif kind == "folder":
        target.mkdir()
    res = run(SCENES[0], "--spp", 1, "-D", "res=8", "-o", target, "-q")
    assert res.returncode == 1, res.stderr
    assert res.stderr.startswith(f"error: {target}:") and len(res.stderr.strip().splitlines()) == 1, res.stderr
    leftovers = [p.name for p in tmp_path.rglob("*") if ".tmp" in p.name]
    assert not leftovers
    if kind == "fifo":
        assert target.is_fifo()
    if kind == "folder":
        assert target.is_dir() and not any(target.iterdir())


def test_a_scene_file_that_is_a_fifo_is_refused_without_blocking(tmp_path):
    import os
    fifo = tmp_path / "scene.xml"
    os.mkfifo(fifo)
    res = subprocess.run([RENDER, str(fifo), "-o", str(tmp_path / "o.exr"), "-q"], capture_output=True, text=True,
                         timeout=30)
    assert res.returncode != 0 and "not a regular file" in res.stderr, res.stderr


def test_the_most_batches_a_render_takes_are_still_readable(tmp_path):
    from harness.engines.render_process import read_render_exr

    out = tmp_path / "many.exr"
    assert run(SCENES[0], "--spp", 1, "--batches", 1363, "-D", "res=2", "-o", out, "-q").returncode == 0
    assert read_render_exr(out, 1363).batches.shape == (1363, 2, 2, 3)
    refused = run(SCENES[0], "--spp", 1, "--batches", 1364, "-D", "res=2", "-o", tmp_path / "more.exr", "-q")
    assert refused.returncode != 0 and "1363" in refused.stderr


def test_a_light_sample_below_the_surface_traces_no_shadow_ray(tmp_path):
    """Half of a constant emitter's light samples lie below a floor: they carry nothing whatever a shadow ray
    finds, and are not traced (direct and path), while the image is the same."""
    import mcval_renderer
    scene = tmp_path / "floor.xml"
    scene.write_text("""<scene version="3.0.0">
    <integrator type="direct"><integer name="emitter_samples" value="1"/><integer name="bsdf_samples" value="0"/>
    </integrator>
    <sensor type="perspective"><float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/></transform>
    </shape>
    <emitter type="constant"/>
</scene>""")
    out = mcval_renderer.render(str(scene), spp=64, batches=1, integrator="direct")
    share = out["stats"]["shadow_rays"] / out["stats"]["camera_rays"]
    assert 0.45 < share < 0.55, share
    # Diffuse 0.5 under radiance 1, every light sample above the floor unblocked: 2 * 0.5 * cos.
    assert abs(out["mean"].mean() - 0.5) < 0.02
