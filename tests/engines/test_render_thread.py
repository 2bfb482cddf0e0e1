"""A render thread's render ends when the thread is closed: an interrupted caller does not wait for it."""
from __future__ import annotations

import time
from pathlib import Path

import pytest

from harness.engines.base import RenderFailed
from harness.engines.ours import OurEngine
from harness.engines.render_thread import RenderThread
from tests.helpers.render_wrappers import write_wrapper

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "plane_point.xml"


def test_closing_ends_a_hung_render_at_once(tmp_path):
    engine = OurEngine(binary=write_wrapper(tmp_path, "hang", "normals"), timeout=600)
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
        out = thread.submit(OurEngine().render, str(SCENE), "normals", 1, 2, 0, {"res": "8"}).result()
    assert out.batches.shape == (2, 8, 8, 3)
