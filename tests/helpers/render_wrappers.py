"""Stand-ins for the `render` binary (pointed at through MCVAL_RENDER) that misbehave on purpose.

Each is a small Python script: for the renders whose arguments contain `target` (e.g. "simple", an
integrator name) it misbehaves; every other render runs the real renderer unchanged. It speaks
`render --serve` too, as the harness's workers run it (see harness/engines/render_worker.py).
"""
from __future__ import annotations

import stat
import sys
from pathlib import Path

REAL_RENDER = Path(__file__).resolve().parents[2] / "build" / "render"

_HEADER = f"""#!{sys.executable}
import os, signal, subprocess, sys, time
real = {str(REAL_RENDER)!r}
"""

# Run as `render --serve` (the harness's worker), the wrapper answers each request itself: it misbehaves
# as the behaviour says (the worker itself crashing, hanging or being killed) or renders that request with
# the real renderer as a command of its own. Run otherwise, it is one render.
_MAIN = """
def render(args, serve):
    scope = {{"args": args, "hit": {target!r} in args, "os": os, "signal": signal, "sys": sys, "time": time,
             "real": real}}
    try:
        exec(BEHAVIOUR, scope)
    except SystemExit as e:
        if not serve:
            raise
        return e.code or 0
    binary = scope.get("real", real)
    if not serve:
        os.execv(binary, [binary, *scope["args"]])
    return subprocess.call([binary, *scope["args"]], stdout=sys.stderr)

def read_count():
    line = sys.stdin.buffer.readline()
    return int(line) if line else None

if sys.argv[1:] == ["--serve"]:
    answers = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    print("mcval-serve 1", file=answers, flush=True)
    while (count := read_count()) is not None:
        args = [sys.stdin.buffer.read(read_count()).decode() for _ in range(count)]
        status = render(args, True)
        sys.stderr.flush()
        print(status, file=answers, flush=True)
else:
    render(sys.argv[1:], False)
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
    # Render ao with the test build's ao_uniform (uniform hemisphere, weighted by 2 cos): ao's mean, more noise.
    "ao_uniform": """
if hit:
    args[args.index("--integrator") + 1] = "ao_uniform"
    real = os.path.join(os.path.dirname(real), "render_with_test_integrators")
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
    path.write_text(_HEADER + f"BEHAVIOUR = {BEHAVIOURS[behaviour]!r}\n" + _MAIN.format(target=target))
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path
