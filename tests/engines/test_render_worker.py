"""Our renders run in long-lived `render --serve` workers: one per binary, reused render after render, and
replaced when one crashes or hangs; the framing carries any argument, and a worker ends with its input."""
import subprocess
from pathlib import Path

import numpy as np
import pytest

from harness.engines import render_worker
from harness.engines.base import RenderFailed
from harness.engines.mcval import McvalEngine
from harness.engines.render_process import render_binary
from harness.engines.render_worker import frame_request
from tests.helpers.render_wrappers import write_wrapper

ROOT = Path(__file__).resolve().parents[2]
SCENE = str(ROOT / "scenes" / "cornell.xml")
PARAMS = {"res": "16"}


def idle_pids(binary: Path) -> list[int]:
    return [w.proc.pid for w in render_worker._idle.get(render_worker._key(binary.resolve()), [])]


def test_renders_reuse_one_worker_and_match_the_module():
    import mcval_renderer
    engine = McvalEngine()
    first = engine.render(SCENE, "ao", 2, 2, 5, PARAMS)
    pids = idle_pids(render_binary())
    second = engine.render(SCENE, "ao", 2, 2, 5, PARAMS)
    assert len(pids) == 1 and idle_pids(render_binary()) == pids
    module = mcval_renderer.render(SCENE, spp=2, seed=5, batches=2, integrator="ao", params=PARAMS)
    assert np.array_equal(first.batches, module["batches"]) and np.array_equal(second.batches, first.batches)


def test_a_crash_fails_one_render_and_the_next_gets_a_new_worker(tmp_path):
    wrapper = write_wrapper(tmp_path, "segfault", "ao")
    engine = McvalEngine(binary=wrapper)
    engine.render(SCENE, "simple", 1, 2, 0, PARAMS)
    before = idle_pids(wrapper)
    with pytest.raises(RenderFailed, match=r"^killed by signal SIGSEGV \(11\)$"):
        engine.render(SCENE, "ao", 1, 2, 0, PARAMS)
    assert idle_pids(wrapper) == []
    engine.render(SCENE, "simple", 1, 2, 0, PARAMS)
    after = idle_pids(wrapper)
    assert len(before) == len(after) == 1 and before != after


def test_a_scene_error_keeps_the_worker_and_names_only_its_own_output(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text('<scene version="3.0.0">\n  <sensor type="perspective"><float name="fov" value="4O"/>'
                   "</sensor>\n</scene>\n")
    engine = McvalEngine()
    engine.render(SCENE, "normals", 1, 2, 0, PARAMS)
    pids = idle_pids(render_binary())
    for _ in range(2):
        with pytest.raises(RenderFailed) as e:
            engine.render(str(bad), "ao", 1, 2, 0)
        assert e.value.reason.startswith("exited with status 1: error: ") and "\n" not in e.value.reason
        assert e.value.output.count("error:") == 1  # this render's lines, not the one before
    assert idle_pids(render_binary()) == pids


def test_a_rebuilt_binary_gets_a_worker_of_its_own(tmp_path):
    import os
    wrapper = write_wrapper(tmp_path, "hang", "no-such-argument")
    McvalEngine(binary=wrapper).render(SCENE, "normals", 1, 2, 0, PARAMS)
    old = render_worker._key(wrapper)
    os.utime(wrapper, ns=(0, 12345))  # as a rebuild changes it
    McvalEngine(binary=wrapper).render(SCENE, "normals", 1, 2, 0, PARAMS)
    assert render_worker._key(wrapper) != old and len(render_worker._idle[render_worker._key(wrapper)]) == 1


def test_any_argument_reaches_the_renderer(tmp_path):
    """Newlines, spaces, non-ASCII and digits at an argument's start cross the framing intact."""
    folder = tmp_path / "2 scènes\nhere"
    folder.mkdir()
    scene = folder / "cornell.xml"
    scene.write_text(Path(SCENE).read_text().replace('filename="', f'filename="{ROOT / "scenes"}/'))
    out = McvalEngine().render(str(scene), "normals", 1, 2, 0, PARAMS)
    assert out.batches.shape == (2, 16, 16, 3) and np.isfinite(out.batches).all()


def serve(data: bytes) -> subprocess.CompletedProcess:
    return subprocess.run([str(render_binary()), "--serve"], input=data, capture_output=True, timeout=60)


def test_serve_answers_each_request_with_its_status_and_ends_with_its_input(tmp_path):
    out = tmp_path / "a.exr"
    good = [SCENE, "-q", "-D", "res=8", "--spp", "1", "-o", str(out)]
    done = serve(frame_request(good) + frame_request(["--no-such-option"]) + frame_request(["--help"]))
    assert done.returncode == 0 and out.exists()
    greeting, *statuses = done.stdout.decode().splitlines()
    assert greeting == render_worker.GREETING.decode()
    assert statuses[0] == "0" and statuses[1] not in ("0", "1", "2") and statuses[2] == "0"
    assert "Usage: render" in done.stderr.decode()  # --help printed to the log, never among the answers


@pytest.mark.parametrize("data, message", [
    (b"two\n", "argument count"),
    (b"1\nfive\n", "argument's length"),
    (b"1\n100\nshort", "ended inside an argument"),
    (b"+1\n", "argument count"),
    (b"1\n-1\n", "argument's length"),
    (b"1\n99999999999999999999\n", "argument's length"),
])
def test_serve_refuses_a_malformed_request(data, message):
    done = serve(data)
    assert done.returncode == 3 and message in done.stderr.decode()
    assert done.stdout == render_worker.GREETING + b"\n"  # and no answer


def test_a_binary_without_serve_renders_one_process_per_render(tmp_path):
    """An older build or a user's script that knows no --serve: the same bits, one process per render."""
    import sys
    script = tmp_path / "render_without_serve.py"
    script.write_text(f"#!{sys.executable}\nimport os, sys\nif sys.argv[1:] == ['--serve']:\n"
                      "    print('scene is required', file=sys.stderr); sys.exit(106)\n"
                      f"os.execv({str(render_binary())!r}, [{str(render_binary())!r}, *sys.argv[1:]])\n")
    script.chmod(0o755)
    import mcval_renderer
    for _ in range(2):
        out = McvalEngine(binary=script).render(SCENE, "ao", 2, 2, 9, PARAMS)
        module = mcval_renderer.render(SCENE, spp=2, seed=9, batches=2, integrator="ao", params=PARAMS)
        assert np.array_equal(out.batches, module["batches"])
    assert "did not start as a render worker" in render_worker._no_serve[render_worker._key(script)]
    assert idle_pids(script) == []


def test_a_worker_killed_while_idle_is_replaced_without_failing_a_render():
    import os
    import signal
    import time
    engine = McvalEngine()
    engine.render(SCENE, "normals", 1, 2, 0, PARAMS)
    (pid,) = idle_pids(render_binary())
    os.kill(pid, signal.SIGKILL)
    time.sleep(0.2)
    assert engine.render(SCENE, "normals", 1, 2, 0, PARAMS).batches.shape == (2, 16, 16, 3)
    assert idle_pids(render_binary()) not in ([], [pid])


def test_a_real_worker_killed_mid_render_fails_that_render_and_the_next_gets_a_new_one():
    import os
    import signal
    import threading
    engine = McvalEngine(timeout=120)
    engine.render(SCENE, "normals", 1, 2, 0, PARAMS)
    (pid,) = idle_pids(render_binary())
    threading.Timer(0.5, os.kill, (pid, signal.SIGKILL)).start()
    with pytest.raises(RenderFailed, match=r"^killed by signal SIGKILL \(9\)$"):
        engine.render(SCENE, "ao", 100000, 1, 0, {"res": "64"})  # minutes of work, were it not killed
    assert engine.render(SCENE, "normals", 1, 2, 0, PARAMS).batches.shape == (2, 16, 16, 3)
    assert pid not in idle_pids(render_binary())
