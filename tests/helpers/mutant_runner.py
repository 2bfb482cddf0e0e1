"""Runs pytest on copies of harness/, each in a child forked from this process: the libraries every run imports
(numpy, scipy, pytest, colour) are imported once, here, and never the harness, which each child imports from
its own copy.

    python mutant_runner.py ROOT < runs.json

runs.json: a list of {"parent": folder holding the copy's harness/, "nodes": test node ids, "out": log file}.
Prints one JSON list of exit codes, in the order of the runs; 13 where a child imported another harness than
its copy (pytest's own codes are 0 to 5).
"""
from __future__ import annotations

import json
import os
import sys

os.environ.update(PYTHONDONTWRITEBYTECODE="1", PYTEST_DISABLE_PLUGIN_AUTOLOAD="1", OPENBLAS_NUM_THREADS="1")
import numpy  # noqa: E402,F401
import scipy.ndimage  # noqa: E402,F401
import scipy.optimize  # noqa: E402,F401
import scipy.special  # noqa: E402,F401
import scipy.stats  # noqa: E402,F401
import colour  # noqa: E402,F401
import pytest  # noqa: E402

#: Children at a time: the two cores.
PARALLEL = 2


def _child(root: str, run: dict) -> int:
    """In the forked child: the copy first on the path, then the project's root (for tests.helpers)."""
    fd = os.open(run["out"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    os.dup2(fd, 1)
    os.dup2(fd, 2)
    os.chdir(run["parent"])
    sys.path[:0] = [run["parent"], root]
    os.environ["PYTHONPATH"] = os.pathsep.join([run["parent"], root])
    import harness
    if os.path.dirname(os.path.abspath(harness.__file__)) != os.path.join(run["parent"], "harness"):
        return 13
    # pytest's own `pythonpath` setting, which would put the root first, is emptied.
    return int(pytest.main(["-q", "-x", "-p", "no:cacheprovider", "--runxfail", "-o", "pythonpath=", "--rootdir", root,
                            "-c", os.path.join(root, "pyproject.toml"), *[os.path.join(root, n) for n in run["nodes"]]]))


def _reap(running: dict[int, int], codes: list[int | None]) -> None:
    """Waits for one child and files its exit code under its run's index."""
    pid, status = os.wait()
    codes[running.pop(pid)] = os.waitstatus_to_exitcode(status)


def main() -> int:
    root = sys.argv[1]
    runs = json.load(sys.stdin)
    codes: list[int | None] = [None] * len(runs)
    running: dict[int, int] = {}  # child's pid -> its run's index
    for i, run in enumerate(runs):
        while len(running) >= PARALLEL:
            _reap(running, codes)
        sys.stdout.flush()
        pid = os.fork()
        if pid == 0:
            code = 1
            try:
                code = _child(root, run)
            finally:
                sys.stdout.flush()
                sys.stderr.flush()
                os._exit(code)
        running[pid] = i
    while running:
        _reap(running, codes)
    print(json.dumps(codes))
    return 0


if __name__ == "__main__":
    sys.exit(main())
