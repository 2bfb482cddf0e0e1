"""Mitsuba's renders in worker processes (harness/engines/mitsuba_worker.py): a PLY face index that segfaults
Mitsuba's loader fails its own render in one line, Mitsuba's own errors come back as they are, the next
render gets a new worker, and a worker that rendered is kept for the next render."""
from pathlib import Path

import pytest

from harness.engines import mitsuba_worker
from harness.engines.base import RenderFailed
from harness.engines.mitsuba_worker import TIMEOUT_ENV, render_timeout

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "plane_point.xml"
PLY = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 0 1\n3 0 1 1000000000\n")


def misbehaving_scenes(folder: Path) -> dict[str, Path]:
    """plane_point.xml as it is ("good"), with a PLY mesh whose face index is 10^9 ("crash": 12 GB past its
    vertices, always unmapped; 10^5 crashes only at times) and with a
    gaussian filter of stddev 3e9 ("hang")."""
    text = SCENE.read_text()
    (folder / "bad.ply").write_text(PLY)
    scenes = {"good": text,
              "crash": text.replace('<emitter type="point">', '<shape type="ply"><string name="filename" '
                                    'value="bad.ply"/><ref id="floor"/></shape><emitter type="point">'),
              "hang": text.replace('<rfilter type="box"/>',
                                   '<rfilter type="gaussian"><float name="stddev" value="3e9"/></rfilter>')}
    for name, xml in scenes.items():
        (folder / f"{name}.xml").write_text(xml)
    return {name: folder / f"{name}.xml" for name in scenes}


def test_a_crash_fails_its_own_render_and_the_next_gets_a_new_worker(mitsuba, tmp_path):
    # The hang (ended at the time limit) is tested through a whole run: tests/commands/test_images.py.
    scenes = misbehaving_scenes(tmp_path)
    with pytest.raises(RenderFailed, match="^Mitsuba was killed by SIGSEGV while loading or rendering crash.xml$"):
        mitsuba.render(str(scenes["crash"]), "simple", 4, 1, 0, {"res": "8"})
    good = mitsuba.render(str(scenes["good"]), "simple", 4, 2, 0, {"res": "8"})
    assert good.batches.shape == (2, 8, 8, 3) and good.scene == str(scenes["good"]) and good.batches.mean() > 0
    (worker,) = mitsuba_worker._idle  # kept for the next render
    again = mitsuba.render(str(scenes["good"]), "simple", 4, 2, 0, {"res": "8"})
    assert mitsuba_worker._idle == [worker] and (again.batches == good.batches).all()


def test_mitsubas_own_error_comes_back_as_it_is(mitsuba, tmp_path):
    broken = tmp_path / "broken.xml"
    broken.write_text(SCENE.read_text().replace('<rfilter type="box"/>', '<rfilter type="no_such_filter"/>'))
    with pytest.raises(RuntimeError, match="no_such_filter") as raised:
        mitsuba.render(str(broken), "simple", 4, 1, 0, {"res": "8"})
    assert not isinstance(raised.value, RenderFailed)


@pytest.mark.parametrize("value", ["0", "nan", "later"])
def test_a_time_limit_that_is_not_a_positive_number_is_refused(monkeypatch, value):
    monkeypatch.setenv(TIMEOUT_ENV, value)
    with pytest.raises(ValueError, match=f"{TIMEOUT_ENV}='{value}': give a positive number of seconds"):
        render_timeout()
