"""The import contract of pyproject.toml ([tool.importlinter]) can fail: a copy of the package with a planted
import of a concrete engine (or of the compiled module) in a suite, an entry or the bench breaks it, and
`lint-imports`, which `make test` runs, exits non-zero naming the import; the copy as it is keeps it."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")


def _copy(tmp_path: Path) -> Path:
    shutil.copytree(ROOT / "harness", tmp_path / "harness", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    return tmp_path


def _lint(folder: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(folder)}
    return subprocess.run([str(LINT_IMPORTS), "--no-cache"], cwd=folder, env=env, capture_output=True, text=True,
                          timeout=300)


@pytest.fixture(scope="module")
def clean_copy(tmp_path_factory):
    return _copy(tmp_path_factory.mktemp("contract"))


def test_the_package_as_it_is_keeps_the_contract(clean_copy):
    res = _lint(clean_copy)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "know no concrete engine KEPT" in res.stdout


@pytest.mark.parametrize("module, planted", [
    ("bench/ladder.py", "from harness.engines.mcval import McvalEngine"),
    ("integrators/registry.py", "from harness.native import renderer_module"),
    ("images/suite.py", "import harness.engines.mitsuba_scene"),
    ("invariance/cell.py", "from harness.engines.nori import to_nori"),
    ("warps/checks.py", "from harness.engines.engine_file import read_engine_file"),
])
def test_a_planted_import_of_a_concrete_engine_fails_lint_imports(tmp_path, module, planted):
    folder = _copy(tmp_path)
    path = folder / "harness" / module
    lines = path.read_text().splitlines(keepends=True)
    # After the module's docstring and `from __future__` line: an import like any other at the top.
    at = next(i for i, line in enumerate(lines) if line.startswith(("import ", "from ")) and "__future__" not in line)
    path.write_text("".join(lines[:at] + [planted + "\n"] + lines[at:]))
    res = _lint(folder)
    assert res.returncode != 0, res.stdout
    assert "know no concrete engine BROKEN" in res.stdout
    importer = "harness." + module[:-3].replace("/", ".")
    assert f"{importer} -> {planted.split()[1]}" in res.stdout, res.stdout
