"""Our engine renders through the `render` CLI in a child process: the same bits as the in-process module,
and a crash, kill, hang, error or missing image becomes a RenderFailed with a one-line reason."""
import time
from pathlib import Path

import numpy as np
import pytest

from harness.engines.base import RenderFailed
from harness.engines.mcval import McvalEngine
from harness.engines.render_process import BASE_TIMEOUT, default_timeout
from tests.helpers.render_wrappers import write_wrapper

ROOT = Path(__file__).resolve().parents[2]
SCENE = str(ROOT / "scenes" / "cornell.xml")
PARAMS = {"res": "24"}


def test_child_process_render_is_bit_identical_to_the_module():
    import mcval_renderer
    mine = McvalEngine().render(SCENE, "simple", 4, 3, 4242, PARAMS)
    module = mcval_renderer.render(SCENE, spp=4, seed=4242, batches=3, integrator="simple", params=PARAMS)
    assert mine.batches.dtype == np.float32 and mine.batches.shape == (3, 24, 24, 3)
    assert np.array_equal(mine.batches, module["batches"])
    assert set(mine.seconds) == {"load", "build", "render", "total"}
    assert 0 < mine.seconds["render"] <= mine.seconds["total"]


def test_one_batch_comes_from_the_mean_layer():
    import mcval_renderer
    mine = McvalEngine().render(SCENE, "ao", 2, 1, 7, PARAMS)
    module = mcval_renderer.render(SCENE, spp=2, seed=7, batches=1, integrator="ao", params=PARAMS)
    assert np.array_equal(mine.batches, module["batches"])


def test_a_scene_error_names_the_status_and_the_message(tmp_path):
    scene = tmp_path / "bad.xml"
    scene.write_text('<scene version="3.0.0">\n  <sensor type="perspective"><float name="fov" value="4O"/>'
                     "</sensor>\n</scene>\n")
    with pytest.raises(RenderFailed) as e:
        McvalEngine().render(str(scene), "ao", 1, 2, 0)
    assert e.value.reason.startswith("exited with status 1: error: ")
    assert 'expected a number, got "4O"' in e.value.reason and "\n" not in e.value.reason


def test_a_segfault_names_the_signal(tmp_path):
    engine = McvalEngine(binary=write_wrapper(tmp_path, "segfault", "ao"))
    with pytest.raises(RenderFailed, match=r"^killed by signal SIGSEGV \(11\)$"):
        engine.render(SCENE, "ao", 1, 2, 0, PARAMS)
    assert engine.render(SCENE, "simple", 1, 2, 0, PARAMS).batches.shape == (2, 24, 24, 3)


def test_a_kill_mid_render_names_the_signal(tmp_path):
    engine = McvalEngine(binary=write_wrapper(tmp_path, "kill", "ao"), timeout=60)
    with pytest.raises(RenderFailed, match=r"^killed by signal SIGKILL \(9\)$"):
        engine.render(SCENE, "ao", 1, 2, 0, PARAMS)


def test_a_hang_ends_at_the_timeout(tmp_path, monkeypatch):
    monkeypatch.setenv("MCVAL_RENDER", str(write_wrapper(tmp_path, "hang", "ao")))
    monkeypatch.setenv("MCVAL_RENDER_TIMEOUT", "1.5")
    start = time.perf_counter()
    with pytest.raises(RenderFailed, match=r"^timed out after 1.5 s$"):
        McvalEngine().render(SCENE, "ao", 1, 2, 0, PARAMS)
    assert time.perf_counter() - start < 10


def test_a_render_that_writes_nothing_fails(tmp_path):
    engine = McvalEngine(binary=write_wrapper(tmp_path, "no_image", "ao"))
    with pytest.raises(RenderFailed, match="^wrote no image$"):
        engine.render(SCENE, "ao", 1, 2, 0, PARAMS)


def test_a_missing_binary_is_a_clear_error(tmp_path):
    with pytest.raises(RuntimeError, match="MCVAL_RENDER") as e:
        McvalEngine(binary=tmp_path / "nothing").render(SCENE, "ao", 1, 2, 0, PARAMS)
    assert not isinstance(e.value, RenderFailed)


def test_default_timeout_grows_with_the_work(monkeypatch):
    monkeypatch.delenv("MCVAL_RENDER_TIMEOUT", raising=False)
    small, large = default_timeout(32, 8, {"res": "128"}), default_timeout(512, 1, {"res": "768"})
    assert BASE_TIMEOUT <= small < large
    monkeypatch.setenv("MCVAL_RENDER_TIMEOUT", "5")
    assert default_timeout(512, 1, {"res": "768"}) == 5


def test_a_relative_render_binary_works(monkeypatch):
    """MCVAL_RENDER=build/render (relative to the working folder): the child, which runs in a
    temporary folder, still finds it."""
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MCVAL_RENDER", "build/render")
    mine = McvalEngine().render(SCENE, "normals", 1, 2, 3, PARAMS)
    assert mine.batches.shape == (2, 24, 24, 3)


def test_a_raw_image_holds_the_batches_and_the_timings(tmp_path):
    import subprocess
    from harness.engines.render_process import read_render_raw, render_binary
    import mcval_renderer
    out = tmp_path / "x.raw"
    subprocess.run([str(render_binary()), SCENE, "--integrator", "ao", "--spp", "2", "--batches", "3", "--seed", "4",
                    "-D", "res=24", "-q", "--raw", "-o", str(out)], check=True)
    got = read_render_raw(out, 3)
    module = mcval_renderer.render(SCENE, spp=2, seed=4, batches=3, integrator="ao", params=PARAMS)
    assert np.array_equal(got.batches, module["batches"]) and got.sampler == "independent"
    assert set(got.seconds) == {"load", "build", "render"} and got.seconds["render"] > 0


@pytest.mark.parametrize("damage, message", [
    (lambda b: b[:-4], "bytes of pixels"),                      # truncated
    (lambda b: b + b"\0", "bytes of pixels"),                    # trailing bytes
    (lambda b: b.replace(b"mcval-raw 1", b"mcval-raw 2"), "not a render --raw header"),
    (lambda b: b.replace(b" 3 load=", b" 2 load="), "2 images where 3 batches"),
    (lambda b: b"\xff" + b, "UnicodeDecodeError"),
])
def test_a_damaged_raw_image_is_refused_in_one_line(tmp_path, damage, message):
    import subprocess
    from harness.engines.render_process import read_render_raw, render_binary
    out = tmp_path / "x.raw"
    subprocess.run([str(render_binary()), SCENE, "--spp", "1", "--batches", "3", "-D", "res=8", "-q", "--raw",
                    "-o", str(out)], check=True)
    out.write_bytes(damage(out.read_bytes()))
    with pytest.raises(RenderFailed, match="^wrote an unreadable image") as e:
        read_render_raw(out, 3)
    assert message in e.value.reason
