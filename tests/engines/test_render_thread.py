"""A render thread's render ends when the thread is closed: an interrupted caller does not wait for it."""
from __future__ import annotations

import time
from pathlib import Path

import pytest

from harness.engines.base import RenderFailed
from harness.engines.mcval import McvalEngine
from harness.engines.render_thread import RenderThread
from tests.helpers.render_wrappers import write_wrapper

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "plane_point.xml"


def test_closing_ends_a_hung_render_at_once(tmp_path):
    engine = McvalEngine(binary=write_wrapper(tmp_path, "hang", "normals"), timeout=600)
    thread = RenderThread()
    future = thread.submit(engine.render, str(SCENE), "normals", 1, 1, 0, {"res": "8"})
    time.sleep(1.0)  # the hung render is running by now
    start = time.perf_counter()
    thread.close()
    assert time.perf_counter() - start < 5
    with pytest.raises(RenderFailed, match="cancelled"):
        future.result()


def test_a_render_run_to_its_end_is_its_result():
    with RenderThread() as thread:
        out = thread.submit(McvalEngine().render, str(SCENE), "normals", 1, 2, 0, {"res": "8"}).result()
    assert out.batches.shape == (2, 8, 8, 3)


def test_workers_start_from_a_thread_while_another_sets_variables(tmp_path):
    """exec reading the live environment while another thread changes it fails with EFAULT: each child gets
    a copy. 40 worker starts from a render thread beside a thread setting and deleting variables."""
    import os
    import threading

    from harness.engines.render_worker import close_workers

    stop, errors = threading.Event(), []

    def churn():
        i = 0
        while not stop.is_set():
            os.environ[f"MCVAL_TEST_CHURN_{i % 40}"] = "x" * (i % 200)
            if i % 40 == 39:
                for k in [k for k in os.environ if k.startswith("MCVAL_TEST_CHURN_")]:
                    os.environ.pop(k, None)
            i += 1

    setter = threading.Thread(target=churn)
    setter.start()
    try:
        with RenderThread() as thread:
            for _ in range(40):
                try:
                    thread.submit(McvalEngine().render, str(SCENE), "normals", 1, 1, 0, {"res": "4"}).result()
                except RenderFailed as e:
                    errors.append(e.reason)
                close_workers()  # the next render starts a worker again
    finally:
        stop.set()
        setter.join()
    assert errors == []


def test_a_nested_cancel_gives_the_outer_one_back():
    """A command engine's calls set the render thread's event again around each call: after one, the
    render's later calls must still be cancelled by it."""
    import threading

    from harness.engines.child_process import cancelled, cancelled_by

    outer = threading.Event()
    with cancelled_by(outer):
        with cancelled_by(outer):
            pass
        outer.set()
        assert cancelled()
    assert not cancelled()
