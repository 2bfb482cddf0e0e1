"""Stand-ins for the `render` binary (pointed at through MCVAL_RENDER) that misbehave on purpose.

Each is a small Python script: for the renders whose arguments contain `target` (e.g. "simple", an
integrator name) it misbehaves; every other render runs the real renderer unchanged.
"""
from __future__ import annotations

import stat
import sys
from pathlib import Path

REAL_RENDER = Path(__file__).resolve().parents[2] / "build" / "render"

_HEADER = f"""#!{sys.executable}
import os, signal, sys, time
real, args = {str(REAL_RENDER)!r}, sys.argv[1:]
hit = {{target!r}} in args
"""

#: What the wrapper does when `target` is among the arguments.
BEHAVIOURS = {
    # Start the real renderer on a long render (a million samples per pixel) and SIGKILL it mid-run:
    # a forked helper kills the process that then runs the renderer (execv keeps the process id).
    "kill": """
if hit:
    args[args.index("--spp") + 1] = "1000000"
    if os.fork() == 0:
        time.sleep(0.5)
        os.kill(os.getppid(), signal.SIGKILL)
        os._exit(0)
""",
    # Die at once of a segmentation fault.
    "segfault": """
if hit:
    os.kill(os.getpid(), signal.SIGSEGV)
""",
    # A scene error from the real renderer: the resolution given is not an integer (exit status 1).
    "scene_error": """
if hit:
    args = [("res=twelve" if a.startswith("res=") else a) for a in args]
""",
    # Hang (until the harness's timeout ends it).
    "hang": """
if hit:
    time.sleep(600)
""",
    # Exit successfully without writing anything.
    "no_image": """
if hit:
    sys.exit(0)
""",
    # Exit successfully with an image whose every pixel is NaN (or -1 for "negative_image").
    "nan_image": """
if hit:
    import numpy, OpenEXR
    out = args[args.index("-o") + 1]
    OpenEXR.File({"type": OpenEXR.scanlineimage}, {"RGB": numpy.full((4, 4, 3), numpy.nan, numpy.float32)}).write(out)
    sys.exit(0)
""",
    "negative_image": """
if hit:
    import numpy, OpenEXR
    out = args[args.index("-o") + 1]
    OpenEXR.File({"type": OpenEXR.scanlineimage}, {"RGB": numpy.full((4, 4, 3), -1, numpy.float32)}).write(out)
    sys.exit(0)
""",
    # Fail with a proper error line but leave a temporary output file behind.
    "leftover": """
if hit:
    out = args[args.index("-o") + 1]
    open(os.path.join(os.path.dirname(out), ".out.exr.tmp123"), "w").close()
    print("error: " + args[0] + ": something failed", file=sys.stderr)
    sys.exit(1)
""",
}


def write_wrapper(folder: Path, behaviour: str, target: str) -> Path:
    """An executable script in `folder` that does `behaviour` (a key of BEHAVIOURS) on the renders
    whose arguments contain `target`, and runs the real renderer otherwise."""
    path = folder / f"render_{behaviour}.py"
    path.write_text(_HEADER.format(target=target) + BEHAVIOURS[behaviour] + "os.execv(real, [real, *args])\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path
