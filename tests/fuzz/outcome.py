"""One render of one scene file, judged: the verdict every fuzz and replay run shares.

Outcomes:
  image       exit 0 and a finite image (non-negative unless `normals`)
  error       exit 1 with one `error:` line naming the scene's folder
  signal      killed by a signal, or a sanitizer report
  hang        no exit within the timeout
  bad-image   exit 0 with NaN/Inf or negative pixels, or no readable image
  unclear     any other exit, or an error that does not name the file
  leftover    a temporary output file survived
The last five are findings.
"""
from __future__ import annotations

import os
import signal
import subprocess
from pathlib import Path

import numpy as np

FINDINGS = ("signal", "hang", "bad-image", "unclear", "leftover")
OUTCOMES = ("image", "error", *FINDINGS)
#: Exit code the sanitizers are told to use, so that their reports count as signals.
SANITIZER_EXIT = 86
SANITIZER_ENV = {"ASAN_OPTIONS": f"exitcode={SANITIZER_EXIT}:detect_leaks=0",
                 "UBSAN_OPTIONS": f"halt_on_error=1:exitcode={SANITIZER_EXIT}:print_stacktrace=1"}


def render_command(render: Path, scene: Path, integrator: str, out: Path, res: int = 32, spp: int = 1) -> list[str]:
    """The `render` call of a fuzz or replay run: small, one thread, quiet."""
    return [str(render), str(scene), "--integrator", integrator, "--spp", str(spp), "-D", f"res={res}",
            "--threads", "1", "-q", "-o", str(out)]


def image_problem(path: Path, signed: bool) -> str | None:
    """What is wrong with an output EXR (unreadable, non-finite, negative where it must not be), or None."""
    import OpenEXR
    try:
        with OpenEXR.File(str(path)) as f:
            values = np.concatenate([np.asarray(c.pixels, np.float64).ravel() for c in f.channels().values()])
    except Exception as e:  # noqa: BLE001 - any unreadable output is the finding
        return f"unreadable output: {e}"
    if not np.all(np.isfinite(values)):
        return f"{np.count_nonzero(~np.isfinite(values))} non-finite values"
    if not signed and np.any(values < 0):
        return f"{np.count_nonzero(values < 0)} negative values"
    return None


def judge(render: Path, scene: Path, integrator: str, timeout: float, **size: int) -> tuple[str, str]:
    """(outcome, detail) of rendering `scene` into out.exr beside it."""
    out = scene.parent / "out.exr"
    out.unlink(missing_ok=True)
    try:
        proc = subprocess.run(render_command(render, scene, integrator, out, **size), capture_output=True,
                              timeout=timeout, env={**os.environ, **SANITIZER_ENV}, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang", f"no exit within {timeout:.0f} s"
    stderr = proc.stderr.decode(errors="replace").strip()
    lines = stderr.splitlines()
    last = lines[-1] if lines else ""
    if any(p.name.startswith(".out.exr.tmp") for p in scene.parent.iterdir()):
        return "leftover", "a temporary output file survived"
    if proc.returncode < 0:
        return "signal", signal.Signals(-proc.returncode).name
    if proc.returncode == SANITIZER_EXIT or "Sanitizer" in stderr or "runtime error:" in stderr:
        report = next((ln for ln in lines if "ERROR" in ln or "runtime error" in ln), last)
        return "signal", "sanitizer: " + report[:200]
    if proc.returncode == 0:
        if not out.is_file():
            return "bad-image", "exit 0 without an image"
        problem = image_problem(out, signed=integrator == "normals")
        return ("bad-image", problem) if problem else ("image", "")
    if proc.returncode == 1 and len(lines) == 1 and last.startswith("error: ") and str(scene.parent) in last:
        return "error", last
    return "unclear", f"exit {proc.returncode}: {last[:200]}"
