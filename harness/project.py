"""Where mcval's project files are: the clone that holds scenes/, references/ and build/.

Run from a clone (or an editable install), that is the folder above the harness package. A non-editable
install (`pip install .`) copies the package into site-packages without those folders, so the harness then
looks for the clone: $MCVAL_PROJECT if set, else the current directory or the nearest parent of it that is a
clone of mcval. Where none is found, PROJECT_ROOT stays the folder above the package and `missing_reason`
says why the suite's scenes are not there.

Public API::

    PROJECT_ROOT     # the clone's folder
    SOURCE_ROOT      # the folder above the harness package that is running
    missing_reason() # "" when the scene suite is there, else one line saying why not
"""
from __future__ import annotations

import os
from pathlib import Path

PROJECT_ENV = "MCVAL_PROJECT"
#: The folder above the harness package that is running: its sources are what a stored cell's code hash reads.
SOURCE_ROOT = Path(__file__).resolve().parents[1]


def is_project(folder: Path) -> bool:
    """Whether `folder` is a clone of mcval: scenes/ beside a pyproject.toml of the project `mcval`."""
    try:
        text = (folder / "pyproject.toml").read_text()
    except OSError:
        return False
    return (folder / "scenes").is_dir() and 'name = "mcval"' in text


def find_project(source: Path = SOURCE_ROOT, cwd: Path | None = None, env: str | None = None) -> Path:
    """The clone the harness works in: `env` ($MCVAL_PROJECT) if given; else `source` (the harness's own
    folder's parent) if it is a clone; else `cwd` or its nearest parent that is one; else `source`."""
    if env:
        return Path(env).expanduser().resolve()
    if is_project(source):
        return source
    here = (cwd or Path.cwd()).resolve()
    return next((p for p in (here, *here.parents) if is_project(p)), source)


PROJECT_ROOT = find_project(env=os.environ.get(PROJECT_ENV))


def missing_reason(root: Path = PROJECT_ROOT) -> str:
    """"" when `root` holds the scene suite, else one line: where it was looked for and how to point at it."""
    if (root / "scenes").is_dir():
        return ""
    if os.environ.get(PROJECT_ENV):
        return f"${PROJECT_ENV} is {os.environ[PROJECT_ENV]}, which has no scenes/ folder: set it to a clone of mcval"
    return (f"mcval's scene suite is not found: this harness runs from {SOURCE_ROOT / 'harness'}, away from a clone "
            f"of mcval (a non-editable install copies no scenes/ or references/), and {Path.cwd()} is not in one: "
            f"run it inside the clone, or set ${PROJECT_ENV} to it")
