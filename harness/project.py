"""Where mcval's project files are: the folder that holds scenes/ and references/ (and, in a clone, build/).

Run from a clone (or an editable install), that is the folder above the harness package. A non-editable
install (`pip install .`) copies the harness into site-packages, and the suite's scenes/ and references/ as
the package data of mcval_suite (setup.py), with no build/. The harness then works in: $MCVAL_PROJECT if set;
else the current directory or the nearest parent of it that is a clone of mcval; else the installed
mcval_suite. Where none is found, PROJECT_ROOT stays the folder above the package and `missing_reason` says
why the suite's scenes are not there.

Public API::

    PROJECT_ROOT     # the clone's folder, or the installed suite's
    SOURCE_ROOT      # the folder above the harness package that is running
    missing_reason() # "" when the scene suite is there, else one line saying why not
"""
from __future__ import annotations

import importlib.util
import os
from pathlib import Path

PROJECT_ENV = "MCVAL_PROJECT"
#: The package that an install (setup.py) gives the suite's scenes/ and references/ as package data.
SUITE_PACKAGE = "mcval_suite"
#: The folder above the harness package that is running: its sources are what a stored cell's code hash reads.
SOURCE_ROOT = Path(__file__).resolve().parents[1]


def is_project(folder: Path) -> bool:
    """Whether `folder` is a clone of mcval: scenes/ beside a pyproject.toml of the project `mcval`."""
    try:
        text = (folder / "pyproject.toml").read_text()
    except OSError:
        return False
    return (folder / "scenes").is_dir() and 'name = "mcval"' in text


def installed_suite() -> Path | None:
    """The folder of the installed suite (SUITE_PACKAGE, holding scenes/ and references/), or None."""
    try:
        spec = importlib.util.find_spec(SUITE_PACKAGE)
    except (ImportError, ValueError):
        return None
    folders = [Path(p) for p in (spec.submodule_search_locations or ())] if spec else []
    return next((p.resolve() for p in folders if (p / "scenes").is_dir()), None)


def find_project(source: Path = SOURCE_ROOT, cwd: Path | None = None, env: str | None = None,
                 installed: Path | None = None) -> Path:
    """The folder the harness works in: `env` ($MCVAL_PROJECT) if given; else `source` (the harness's own
    folder's parent) if it is a clone; else `cwd` or its nearest parent that is one; else `installed` (the
    installed suite, installed_suite()) if there is one; else `source`."""
    if env:
        return Path(env).expanduser().resolve()
    if is_project(source):
        return source
    here = (cwd or Path.cwd()).resolve()
    return next((p for p in (here, *here.parents) if is_project(p)), installed or source)


PROJECT_ROOT = find_project(env=os.environ.get(PROJECT_ENV), installed=installed_suite())


def missing_reason(root: Path = PROJECT_ROOT) -> str:
    """"" when `root` holds the scene suite, else one line: where it was looked for and how to point at it."""
    if (root / "scenes").is_dir():
        return ""
    if os.environ.get(PROJECT_ENV):
        return f"${PROJECT_ENV} is {os.environ[PROJECT_ENV]}, which has no scenes/ folder: set it to a clone of mcval"
    return (f"mcval's scene suite is not found: this harness runs from {SOURCE_ROOT / 'harness'}, away from a clone "
            f"of mcval (a non-editable install copies no scenes/ or references/), and {Path.cwd()} is not in one: "
            f"run it inside the clone, or set ${PROJECT_ENV} to it")
