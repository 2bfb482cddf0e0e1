"""Our renderer in a child process: a long-lived `render --serve` worker (see render_worker) writes each
render's images raw (`--raw`) into a temporary folder, and we read them back.

A crash (SIGSEGV, an Embree abort), a kill or a hang of the renderer then ends only that render (and
its worker, which the next render replaces), as a RenderFailed with a one-line reason, and never the
harness.

Environment:

* MCVAL_RENDER: the `render` binary to run (default: build/render under the repository root);
* MCVAL_RENDER_TIMEOUT: seconds after which a render is ended (default: `default_timeout`).
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from harness.engines.base import RenderFailed
from harness.engines.child_process import run_child
from harness.engines.render_worker import NoServe, last_line, run_in_worker
from harness.project import PROJECT_ROOT as ROOT

RENDER_ENV = "MCVAL_RENDER"
TIMEOUT_ENV = "MCVAL_RENDER_TIMEOUT"
#: Threads per render of mcval's renderer (default: every core; the image does not depend on it); set for the workers
#: of an embedded cluster, which share this machine's cores.
THREADS_ENV = "MCVAL_THREADS"
#: Seconds every render is allowed, whatever its size.
BASE_TIMEOUT = 600.0
#: Further seconds allowed per camera sample (spp x batches x pixels): 100x what the slowest
#: integrator needs on the 530k-triangle mesh.
SECONDS_PER_SAMPLE = 1e-5
#: Pixels assumed when the scene's resolution is not given as the `res` parameter.
DEFAULT_PIXELS = 512 * 512


@dataclass
class ChildRender:
    """What one run of the `render` CLI produced.

    batches: (K, H, W, 3) float32, exactly as the renderer wrote them.
    seconds: "load", "build" (BVH) and "render", as measured inside the renderer (from the EXR header).
    """

    batches: np.ndarray
    seconds: dict[str, float]
    sampler: str = ""  # as the file's header names it (mcval.sampler)


def render_binary() -> Path:
    """The `render` binary: $MCVAL_RENDER if set, else build/render under the repository root."""
    return Path(os.environ.get(RENDER_ENV) or ROOT / "build" / "render")


def default_timeout(spp: int, batches: int, params: dict[str, str] | None = None) -> float:
    """Seconds a render may take: $MCVAL_RENDER_TIMEOUT if set, else BASE_TIMEOUT (600 s) plus
    SECONDS_PER_SAMPLE per camera sample."""
    if os.environ.get(TIMEOUT_ENV):
        return float(os.environ[TIMEOUT_ENV])
    try:
        pixels = int((params or {})["res"]) ** 2
    except (KeyError, ValueError):
        pixels = DEFAULT_PIXELS
    return BASE_TIMEOUT + SECONDS_PER_SAMPLE * spp * max(batches, 1) * pixels


def read_render_exr(path: Path, batches: int) -> ChildRender:
    """The batches (`batch<k>.R/G/B` layers, or `R,G,B` for one batch) and timings of a `render` EXR."""
    from harness.exr import read_layers

    try:
        layers, header = read_layers(path)
        names = [f"batch{k}" for k in range(batches)] if "batch0" in layers or batches > 1 else ["RGB"]
        missing = [n for n in names if n not in layers]
        if missing:
            raise RenderFailed(f"wrote an image without the layer(s) {', '.join(missing)}")
        images = np.stack([layers[n] for n in names])
        seconds = {key: float(np.ravel(header[f"mcval.{name}"])[0])
                   for key, name in (("load", "loadSeconds"), ("build", "bvhSeconds"), ("render", "renderSeconds"))}
        sampler = str(header.get("mcval.sampler", ""))
    except RenderFailed:
        raise
    except Exception as e:  # a truncated or foreign file, or one without the renderer's attributes
        raise RenderFailed(f"wrote an unreadable image ({type(e).__name__}: {e})") from e
    return ChildRender(images, seconds, sampler)


def read_render_raw(path: Path, batches: int) -> ChildRender:
    """The images and timings of a `render --raw` file (renderer/raw_output.h): K batches, or the mean of one."""
    try:
        with open(path, "rb") as f:
            words = f.readline(4096).decode("ascii").split()
            if len(words) != 9 or words[:2] != ["mcval-raw", "1"]:
                raise ValueError(f"not a render --raw header: {' '.join(words)[:80]!r}")
            width, height, images = (int(w) for w in words[2:5])
            fields = dict(w.split("=", 1) for w in words[5:])
            if images != batches:
                raise ValueError(f"{images} images where {batches} batches were asked for")
            count = images * height * width * 3
            data = np.fromfile(f, dtype="<f4", count=count)
            if data.size != count or f.read(1):
                raise ValueError(f"{data.size * 4} bytes of pixels where {count * 4} were expected")
        seconds = {key: float(fields[key]) for key in ("load", "bvh", "render")}
        return ChildRender(data.reshape(images, height, width, 3),
                           {"load": seconds["load"], "build": seconds["bvh"], "render": seconds["render"]},
                           fields.get("sampler", ""))
    except (OSError, ValueError, KeyError, UnicodeDecodeError) as e:
        raise RenderFailed(f"wrote an unreadable image ({type(e).__name__}: {e})") from e


def run_render(scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None, timeout: float | None = None,
               binary: str | Path | None = None, sampler: str | None = None) -> ChildRender:
    """Render `SCENE --integrator I --spp N --batches K --seed S [--sampler X] -D name=value ... -q --raw
    -o TMP.raw` in a worker of `binary`, into a temporary folder (deleted afterwards), and read the images. `timeout` in seconds (default:
    `default_timeout`); `binary` defaults to `render_binary()`. Raises RenderFailed on a crash, a kill,
    a timeout, a non-zero exit or a missing image; RuntimeError if the binary does not exist."""
    # Absolute: the child runs in a temporary folder, where a relative path would not resolve.
    binary = (Path(binary) if binary is not None else render_binary()).resolve()
    if not os.access(binary, os.X_OK):
        raise RuntimeError(f"the renderer {binary} does not exist or is not executable: run `make build`, "
                           f"or point {RENDER_ENV} at a `render` binary")
    timeout = default_timeout(spp, batches, params) if timeout is None else timeout
    with tempfile.TemporaryDirectory(prefix="mcval-render-") as tmp:
        command = [str(Path(scene).resolve()), "--integrator", integrator, "--spp", str(spp),
                   "--batches", str(batches), "--seed", str(seed)]
        if sampler:
            command += ["--sampler", sampler]
        for name, value in (params or {}).items():
            command += ["-D", f"{name}={value}"]
        if os.environ.get(THREADS_ENV):
            command += ["--threads", os.environ[THREADS_ENV]]
        out = Path(tmp) / "render.raw"
        try:
            status, tail = run_in_worker(binary, command + ["-q", "--raw", "-o", str(out)], timeout)
        except NoServe:
            # A binary without --serve (an older build, a user's script): one process per render, and the
            # options every `render` has.
            out = Path(tmp) / "render.exr"
            run_child([str(binary), *command, "-q", "-o", str(out)], Path(tmp), Path(tmp) / "output.txt", timeout)
            status, tail = 0, ""
        if status:
            raise RenderFailed(f"exited with status {status}: {last_line(tail)}", tail)
        if not out.exists():
            raise RenderFailed("wrote no image")
        return read_render_raw(out, batches) if out.suffix == ".raw" else read_render_exr(out, batches)
