"""An engine file's renderer, call by call: a good one renders K independent batches; every way a call can go
wrong is a RenderFailed of one line (with the last lines of its output), never an exception of the harness."""
import re
import sys
import time

import numpy as np
import pytest

from harness.comparison.compare import compare_summaries
from harness.comparison.summary import summarize
from harness.engines import child_process
from harness.engines.base import RenderFailed
from harness.engines.command import CommandEngine, call_seed, call_shares
from harness.images.suite import SCENES_DIR
from tests.helpers.foreign_renderers import write_engine

SCENE = str(SCENES_DIR / "plane_point.xml")
PARAMS = {"res": "8"}


def _render(tmp_path, behaviour: str, integrator: str = "simple", extra: str = "", batches: int = 2):
    engine = CommandEngine.from_path(write_engine(tmp_path, behaviour, extra=extra))
    return engine.render(SCENE, integrator, 4, batches, 7, PARAMS)


def _failure(tmp_path, behaviour: str, **kwargs) -> RenderFailed:
    with pytest.raises(RenderFailed) as e:
        _render(tmp_path, behaviour, **kwargs)
    return e.value


def test_a_good_renderer_gives_independent_batches_of_the_asked_size(tmp_path):
    result = _render(tmp_path, "faithful", batches=3)
    assert result.batches.shape == (3, 8, 8, 3) and result.engine == "faithful"
    assert not np.array_equal(result.batches[0], result.batches[1])  # distinct seeds per call
    assert result.seconds["render"] > 0 and result.seconds["total"] >= result.seconds["render"] * 0.5
    assert len({call_seed(7, k) for k in range(64)}) == 64 and all(0 <= call_seed(s, 3) < 2**31 for s in (0, 2**40))


def test_jobs_run_calls_at_once_with_the_same_images(tmp_path):
    one = _render(tmp_path, "faithful", batches=4)
    (tmp_path / "two").mkdir()
    both = _render(tmp_path / "two", "faithful", batches=4, extra="jobs = 2\n")
    assert np.array_equal(one.batches, both.batches)


def test_a_renderer_given_batches_renders_a_share_of_them_in_each_call(tmp_path):
    result = _render(tmp_path, "batched", batches=5, extra="jobs = 2\n")
    assert result.batches.shape == (5, 8, 8, 3) and len({b.tobytes() for b in result.batches}) == 5
    assert sorted((tmp_path / "calls.log").read_text().split()) == ["2", "3"]  # call_shares(5, 2): one call a job
    assert call_shares(8, 2) == [4, 4] and call_shares(8, 1) == [8] and call_shares(2, 4) == [1, 1]


def test_a_call_without_a_layer_it_was_asked_for_fails_naming_it(tmp_path):
    reason = _failure(tmp_path, "batched_short", batches=4).reason
    assert reason.startswith("wrote no layer batch3 (1 of the 4 it was asked for missing)"), reason


@pytest.mark.parametrize("behaviour", ["y_half", "layer"])
def test_y_and_layered_images_are_read_as_rgb(tmp_path, behaviour):
    result = _render(tmp_path, behaviour)
    assert result.batches.shape == (2, 8, 8, 3) and np.allclose(result.batches, 0.25)


@pytest.mark.parametrize("behaviour, reason", [
    ("no_image", "wrote no image"),
    ("not_exr", "wrote a file that is not a readable EXR image"),
    ("wrong_size", "wrote a 4x4 image, expected 8x8"),
    ("no_rgb", "has no R, G, B or Y channels (it has U, V)"),
])
def test_a_bad_image_is_one_line(tmp_path, behaviour, reason):
    assert reason in _failure(tmp_path, behaviour).reason


def test_a_failed_call_keeps_its_last_50_lines(tmp_path):
    failure = _failure(tmp_path, "exit")
    assert failure.reason == "exited with status 3: error: cannot parse"
    lines = failure.output.splitlines()
    assert len(lines) == 50 and lines[-1] == "error: cannot parse" and lines[0] == "progress 31"


def test_a_hung_renderer_is_ended_by_the_timeout(tmp_path):
    assert _failure(tmp_path, "hang", extra="timeout = 1\n").reason == "timed out after 1 s"


def test_a_renderer_printing_without_end_is_ended(tmp_path, monkeypatch):
    monkeypatch.setattr(child_process, "OUTPUT_LIMIT", 1 << 20)
    assert _failure(tmp_path, "spam").reason == "printed more than 1 MB and was ended"


def test_an_integrator_not_in_the_table_fails_the_render(tmp_path):
    path = write_engine(tmp_path, "faithful")
    path.write_text(path.read_text().replace('ao = "ao"\n', ""))
    with pytest.raises(RenderFailed, match="has no integrator for ao"):
        CommandEngine.from_path(path).render(SCENE, "ao", 4, 1, 0, PARAMS)


@pytest.mark.parametrize("behaviour, kind", [("nan", "nonfinite"), ("negative", "negative")])
def test_nan_and_negative_pixels_fail_the_comparison(tmp_path, behaviour, kind):
    result = _render(tmp_path, behaviour, batches=4)
    clean = np.full((4, 8, 8, 3), 0.25, np.float32) + np.random.default_rng(0).normal(0, 0.01, (4, 8, 8, 3))
    comparison = compare_summaries(summarize(result.batches), summarize(clean.astype(np.float32)), 0.01)
    assert not comparison.passed
    assert getattr(comparison.finite.test, kind) >= 1 and comparison.finite.side == "test"


def test_a_failed_call_ends_the_calls_running_beside_it(tmp_path):
    """With jobs = 2, the first call's failure ends the hanging second one instead of waiting for it."""
    script = tmp_path / "half.py"
    script.write_text(f"#!{sys.executable}\nimport sys, time\nif int(sys.argv[4]) % 2: time.sleep(600)\n"
                      "sys.exit(5)\n")
    script.chmod(0o755)
    engine = tmp_path / "half.toml"
    engine.write_text('name = "half"\njobs = 2\ncommand = ["{here}/half.py", "{scene}", "{output}", "{spp}", '
                      '"{seed}"]\n[integrators]\nsimple = "simple"\n')
    start = time.monotonic()
    with pytest.raises(RenderFailed, match="exited with status 5"):
        CommandEngine.from_path(engine).render(SCENE, "simple", 4, 2, 0, PARAMS)
    assert time.monotonic() - start < 30


def _script(path, body: str):
    path.write_text(f"#!{sys.executable}\nimport sys, os\n{body}\n")
    path.chmod(0o755)
    return path


DIRTY = b"v1 \x00\x01\x1b[31m\x7f \xff\xfe \xed\xa0\x80 end"


def test_a_version_of_100_mb_and_control_characters_is_bounded_and_safe(tmp_path):
    _script(tmp_path / "ver.py", f"sys.stdout.buffer.write({DIRTY!r} + b'x' * 100_000_000 + b'\\nsecond line\\n')")
    engine = CommandEngine.from_path(write_engine(tmp_path, "faithful", extra='version = ["{here}/ver.py"]\n'))
    version = engine.describe()["version"]
    assert version.startswith("v1 \\x00\\x01\\x1b[31m\\x7f \ufffd\ufffd") and len(version) < 5000, version[:200]
    assert "more characters]" in version and "second line" not in version
    assert len(engine.version()) < 6000


def test_a_failed_call_printing_control_characters_is_one_safe_line(tmp_path):
    _script(tmp_path / "dirty.py", f"sys.stdout.buffer.write({DIRTY!r} * 3 + b'\\n' + {DIRTY!r}); sys.exit(2)")
    engine = tmp_path / "dirty.toml"
    engine.write_text('name = "dirty"\ncommand = ["{here}/dirty.py", "{scene}", "{output}"]\n'
                      '[integrators]\nsimple = "simple"\n')
    with pytest.raises(RenderFailed) as e:
        CommandEngine.from_path(engine).render(SCENE, "simple", 4, 1, 0, PARAMS)
    for text in (e.value.reason, e.value.output):
        assert "\\x00\\x01\\x1b[31m\\x7f" in text and not any(ord(c) < 32 and c != "\n" for c in text), text


@pytest.mark.parametrize("seconds", ["-1e30", "float('nan')", "float('inf')", "-1.0"])
def test_a_render_time_that_is_not_a_time_fails_the_call_with_engine_and_value(tmp_path, seconds):
    _script(tmp_path / "timed.py", "import numpy as np, OpenImageIO as oiio\n"
                                   "spec = oiio.ImageSpec(8, 8, 3, 'float')\n"
                                   f"spec.attribute('timed.renderSeconds', {seconds})\n"
                                   "out = oiio.ImageOutput.create(sys.argv[2]); out.open(sys.argv[2], spec)\n"
                                   "out.write_image(np.full((8, 8, 3), 0.25, np.float32)); out.close()")
    engine = tmp_path / "timed.toml"
    engine.write_text('name = "timed"\ncommand = ["{here}/timed.py", "{scene}", "{output}"]\n'
                      '[integrators]\nsimple = "simple"\n')
    value = f"{float(eval(seconds)):g}"
    expected = rf"timed wrote renderSeconds = {re.escape(value)} in its EXR .*finite.*at least 0"
    with pytest.raises(RenderFailed, match=expected):
        CommandEngine.from_path(engine).render(SCENE, "simple", 4, 1, 0, PARAMS)
