"""The harness finds mcval's clone where a non-editable install put the package elsewhere: in the current
directory or a parent of it, or at $MCVAL_PROJECT; where there is none, selecting the suite's cases says why."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from harness.project import SOURCE_ROOT, find_project, is_project, missing_reason

PROJECT = Path(__file__).resolve().parents[1]


def test_a_clone_is_found_from_inside_it(tmp_path):
    assert is_project(PROJECT) and not is_project(tmp_path)
    installed = tmp_path / "site-packages"
    assert find_project(installed, cwd=PROJECT / "scenes" / "real") == PROJECT
    assert find_project(installed, cwd=tmp_path) == installed
    assert find_project(PROJECT, cwd=tmp_path) == PROJECT == SOURCE_ROOT
    assert find_project(installed, cwd=tmp_path, env=str(PROJECT)) == PROJECT
    suite = tmp_path / "mcval_suite"
    assert find_project(installed, cwd=tmp_path, installed=suite) == suite  # pip install . (setup.py)
    assert find_project(installed, cwd=PROJECT, installed=suite) == PROJECT  # a clone comes first
    assert missing_reason(PROJECT) == "" and "not found" in missing_reason(installed)


def test_an_installed_copy_runs_the_suite_inside_the_clone_and_says_why_not_elsewhere(tmp_path):
    """The harness copied out of the clone, as `pip install .` does: imported from there, it finds the scenes
    from inside the clone, and from outside it refuses to select cases, with the reason (no run of 0 cases)."""
    site = tmp_path / "site"
    shutil.copytree(PROJECT / "harness", site / "harness", ignore=shutil.ignore_patterns("__pycache__"))
    # (sys.modules: as if no suite were installed, which an editable install of the project's .venv maps)
    code = ("import sys; sys.modules['mcval_suite'] = None; import harness.images.suite as s; print(s.ROOT); print(len(s.select_cases(None, integrators=('ao',))))")
    env = {**os.environ, "PYTHONPATH": str(site)}
    env.pop("MCVAL_PROJECT", None)
    inside = subprocess.run([sys.executable, "-c", code], cwd=PROJECT / "scenes", env=env, capture_output=True,
                            text=True, check=True)
    from harness.images.suite import select_cases
    assert inside.stdout.split() == [str(PROJECT), str(len(select_cases(None, integrators=("ao",))))]
    outside = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert outside.returncode == 1 and "ValueError: mcval's scene suite is not found: this harness runs from " \
        f"{site / 'harness'}" in outside.stderr
