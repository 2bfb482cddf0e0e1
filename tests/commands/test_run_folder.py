"""results/latest moves to a run only once it is complete; an interrupted or failed run leaves it, and
its partial folder, and says so in one line."""
import json
import os

from harness.cli import main
from harness.engines.mcval import McvalEngine
from harness.results import latest_run, new_run_dir

CASE = ["images", "--only", "plane_point:normals"]


def test_new_run_dir_leaves_latest_alone(tmp_path):
    first = new_run_dir(tmp_path)
    assert latest_run(tmp_path) is None and not (tmp_path / "latest").exists()
    os.symlink(first.name, tmp_path / "latest")
    assert new_run_dir(tmp_path) != first and latest_run(tmp_path) == first.name


def test_an_interrupted_run_leaves_latest_at_the_previous_complete_run(tmp_path, monkeypatch, capsys):
    out = tmp_path / "results"
    assert main([*CASE, "--out", str(out)]) == 0
    complete = latest_run(out)
    assert complete and (out / complete / "results.json").exists()

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    with monkeypatch.context() as m:
        m.setattr(McvalEngine, "render", interrupt)
        capsys.readouterr()
        assert main([*CASE, "--out", str(out)]) == 130
    message = capsys.readouterr().err.strip().splitlines()[-1]
    partial = sorted(p.name for p in out.iterdir() if p.name != complete and not p.is_symlink())
    assert len(partial) == 1 and not (out / partial[0] / "results.json").exists()
    assert message == (f"interrupted: partial output in {out / partial[0]}/; "
                       f"{out / 'latest'} still points at {complete}")
    assert latest_run(out) == complete

    # The next complete run compares with the last complete one, and moves `latest`.
    assert main([*CASE, "--out", str(out)]) == 0
    newest = latest_run(out)
    assert newest not in (complete, partial[0])
    assert json.loads((out / newest / "results.json").read_text())["baseline"] == complete


def test_a_run_that_dies_of_an_error_exits_2_and_leaves_latest(tmp_path, monkeypatch, capsys):
    out = tmp_path / "results"

    def broken(*args, **kwargs):
        raise TypeError("a bug in the harness")

    # A case's own failures (a render's, even an unforeseen one) cost that case; the run dies of an error
    # outside every case, here in running them.
    monkeypatch.setattr("harness.images.run.run_images", broken)
    assert main([*CASE, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "a bug in the harness" in err
    assert "stopped: partial output in " in err and f"{out / 'latest'} was not created" in err
    assert latest_run(out) is None


def test_sigterm_ends_a_run_like_ctrl_c(tmp_path):
    """A CI time-out or `kill` (SIGTERM) stops the hung render and names the partial output."""
    import signal
    import subprocess
    import sys
    import time
    from pathlib import Path

    from tests.helpers.render_wrappers import write_wrapper

    wrapper = write_wrapper(tmp_path, "hang", "normals")
    out = tmp_path / "results"
    root = Path(__file__).resolve().parents[2]
    proc = subprocess.Popen([sys.executable, "-m", "harness", *CASE, "--out", str(out)], cwd=root,
                            env={**os.environ, "MCVAL_RENDER": str(wrapper)}, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if out.exists() and any(out.iterdir()):
            break
        time.sleep(0.2)
    time.sleep(2)  # the render child is running (and hanging) by now
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted: partial output in" in err
    assert latest_run(out) is None


def test_a_warps_only_run_does_not_take_the_image_baseline(tmp_path):
    out = tmp_path / "results"
    assert main([*CASE, "--out", str(out)]) == 0
    images_run = latest_run(out)
    assert main(["warps", "--only", "tent", "--no-mitsuba", "--samples", "20000", "--out", str(out)]) in (0, 1)
    assert latest_run(out) != images_run
    assert main([*CASE, "--out", str(out)]) == 0
    assert json.loads((out / latest_run(out) / "results.json").read_text())["baseline"] == images_run
