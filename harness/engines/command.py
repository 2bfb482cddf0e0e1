"""A renderer described by an engine file (docs/engines.md): one call of its command per image (or, where the
command holds {batches}, per share of a case's images), each in a temporary folder of its own, with the scene
file the harness writes for it (scene_writers: written_scene, or nori/to_nori for scene_format = "nori")."""
from __future__ import annotations

import math
import os
import tempfile
import threading
import time
import xml.etree.ElementTree as ET
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait
from functools import cached_property
from pathlib import Path

import numpy as np

from harness.engines.base import Engine, RenderFailed, RenderResult
from harness.engines.child_process import cancelled_by, current_cancel, run_child
from harness.engines.engine_file import EngineFile, read_engine_file
from harness.engines.render_process import THREADS_ENV, default_timeout
from harness.engines.scene_writers import READS_PARAMETERS, SCENE_WRITERS
from harness.exr import ExrError, read_image, read_layers
from harness.foreign_text import FOREIGN_LIMIT, foreign

#: Seconds the version command may take.
VERSION_TIMEOUT = 30.0
#: Bytes the version command may print before it is ended (only its first line is read).
VERSION_OUTPUT_LIMIT = 1 << 20


def call_seed(seed: int, k: int) -> int:
    """The seed of a case's k-th call: distinct per (seed, k), in [0, 2^31)."""
    return (seed * 1_000_003 + k * 7919 + 1) % 2**31


def call_shares(batches: int, jobs: int) -> list[int]:
    """How many of a case's `batches` images each call renders where the command holds {batches}: one call per
    job that may run at once, the images shared as evenly as they go."""
    calls = max(1, min(jobs, batches))
    return [batches // calls + (k < batches % calls) for k in range(calls)]


def read_call_images(output: Path, count: int) -> tuple[np.ndarray, dict[str, object]]:
    """A call's `count` images, (count, H, W, 3): one is any RGB image of the EXR (read_image); more are its
    layers batch0 ... batch<count-1>. RenderFailed naming the layers it lacks."""
    if count == 1:
        image, attributes = read_image(output)
        return image[None], attributes
    layers, attributes = read_layers(output)
    missing = [f"batch{k}" for k in range(count) if f"batch{k}" not in layers]
    if missing:
        raise RenderFailed(f"wrote no layer {missing[0]} ({len(missing)} of the {count} it was asked for missing): "
                           f"a call asked for {{batches}} = {count} writes batch0.R/G/B ... batch{count - 1}.R/G/B")
    return np.stack([layers[f"batch{k}"] for k in range(count)]), attributes


def render_seconds(attributes: dict[str, object]) -> float | None:
    """The render time an EXR carries: a float attribute whose name ends in renderSeconds."""
    for name, value in attributes.items():
        if name.endswith("renderSeconds"):
            try:
                return float(np.ravel(value)[0])
            except (TypeError, ValueError, IndexError):
                return None
    return None


class CommandEngine(Engine):
    """The renderer of an engine file. Seconds: "render" (the calls' render times, summed: the EXR's
    renderSeconds where it carries one, else the call's wall time) and "total" (wall clock)."""

    render_timing = "each call's renderSeconds attribute if its EXR has one, else the call's wall time"
    renders_elsewhere = True
    has_warps = False

    def __init__(self, file: EngineFile, sampler: str | None = None) -> None:
        if sampler not in (None, "independent"):
            raise ValueError(f"{file.name}: an engine file's renderer samples as its scene says, and the harness "
                             f"gives it the independent sampler, not {sampler}")
        self.file = file
        self.name = file.name
        self.label = self.name if sampler is None else f"{self.name}/{sampler}"

    def __reduce__(self):
        return CommandEngine, (self.file, None if self.label == self.name else "independent")

    @classmethod
    def from_path(cls, path: str | Path, sampler: str | None = None) -> "CommandEngine":
        return cls(read_engine_file(path), sampler)

    @property
    def integrators(self) -> tuple[str, ...]:
        return tuple(self.file.integrators)

    def integrator_mapping(self, integrator: str) -> str | None:
        """Its engine file's `[integrators]` line: the <integrator type> its renderer reads, in its dialect."""
        theirs = self.file.integrators.get(integrator)
        return None if theirs is None else f'<integrator type="{theirs}"> ({self.file.scene_format} scene)'

    def draws_integrator_estimator(self, integrator: str) -> bool:
        """Unless its engine file lists `integrator` under other_estimators."""
        return integrator not in self.file.other_estimators

    def reads_integrator_parameters(self, integrator: str) -> bool:
        """Where its dialect's writer hands the scene's own values of the integrator's parameters on: Mitsuba's,
        for an integrator that has parameters (copied into the renderer's <integrator>); Nori's, for direct
        mapped to one of Nori's direct_ems, direct_mats, direct_mis (the strategy those values select)."""
        theirs = self.file.integrators.get(integrator)
        return theirs is not None and READS_PARAMETERS[self.file.scene_format](integrator, theirs)

    @cached_property
    def _version_line(self) -> str:
        """The first line the version command printed (bounded and safe: harness/foreign_text.py), or why
        there is none. It runs as a render call does (run_child): its own session, a time limit, its
        output to a file of which only the start is read."""
        if not self.file.version:
            return "no version command"
        words = [w.replace("{here}", str(self.file.here)) for w in self.file.version]
        with tempfile.TemporaryDirectory(prefix=f"mcval-{self.name}-version-") as tmp:
            log = Path(tmp) / "version.log"
            try:
                run_child(words, Path(tmp), log, VERSION_TIMEOUT, output_limit=VERSION_OUTPUT_LIMIT)
            except OSError as e:
                return foreign(f"version command failed: {e.strerror or e}")
            except RenderFailed as e:
                if log.stat().st_size <= VERSION_OUTPUT_LIMIT:  # (ended for printing on: its first line counts)
                    return f"version command failed: {e.reason}"
            with open(log, "rb") as f:
                head = f.read(4 * FOREIGN_LIMIT)
        line = next((line.strip() for line in head.decode(errors="replace").split("\n") if line.strip()), "")
        return foreign(line) if line else "(version command printed nothing)"

    def version(self) -> str:
        return f"{self.name} {self._version_line} ({self.file.path}: {' '.join(self.file.command)})"

    def describe(self) -> dict[str, str]:
        """Provenance for reports: the engine file, its command and the version it printed."""
        return {"name": self.name, "file": str(self.file.path), "command": " ".join(self.file.command),
                "version": self._version_line}

    def _threads(self) -> int:
        if os.environ.get(THREADS_ENV):
            return int(os.environ[THREADS_ENV])
        return max(1, (os.cpu_count() or 1) // self.file.jobs)

    def _call(self, folder: Path, scene: Path, values: dict[str, str], count: int, width: int, height: int,
              timeout: float, cancel: threading.Event | None = None) -> tuple[np.ndarray, float]:
        """One call: its `count` images and render seconds. RenderFailed on every way it can fail."""
        folder.mkdir()
        output = folder / "image.exr"
        fields = {**values, "batches": str(count), "scene": str(scene), "output": str(output),
                  "here": str(self.file.here)}
        command = [w.format(**fields) for w in self.file.command]
        start = time.perf_counter()
        try:
            run_child(command, folder, folder.parent / f"{folder.name}.log", timeout, cancel)
        except OSError as e:
            raise RenderFailed(f"cannot run {command[0]}: {e.strerror or e}") from None
        wall = time.perf_counter() - start
        if not output.exists():
            raise RenderFailed(f"wrote no image at {{output}} (seed {values['seed']})")
        try:
            images, attributes = read_call_images(output, count)
        except ExrError as e:
            raise RenderFailed(foreign(f"wrote a file that is not a readable EXR image: {e}")) from None
        if images.shape[1:3] != (height, width):
            raise RenderFailed(f"wrote a {images.shape[2]}x{images.shape[1]} image, expected {width}x{height}")
        seconds = render_seconds(attributes)
        # A time the bench would plot and divide by: a negative, NaN or infinite one is the renderer's error.
        if seconds is not None and not (math.isfinite(seconds) and seconds >= 0):
            raise RenderFailed(f"{self.name} wrote renderSeconds = {seconds:g} in its EXR (seed {values['seed']}): "
                               "a render time must be a finite number of seconds, at least 0")
        return images, wall if seconds is None else seconds

    def render(self, scene: str, integrator: str, spp: int, batches: int, seed: int,
               params: dict[str, str] | None = None) -> RenderResult:
        """K calls of the command with seeds call_seed(seed, k), or where it holds {batches} one call per job
        (call_shares); RenderFailed naming the first that fails."""
        start = time.perf_counter()
        theirs = self.file.integrators.get(integrator)
        if theirs is None:
            raise RenderFailed(f"{self.name} has no integrator for {integrator} (its engine file's [integrators])")
        shares = call_shares(batches, self.file.jobs) if self.file.renders_batches else [1] * batches
        timeout = self.file.timeout or default_timeout(spp, max(shares), params)
        with tempfile.TemporaryDirectory(prefix=f"mcval-{self.name}-") as tmp:
            try:
                text, width, height, meshes = SCENE_WRITERS[self.file.scene_format](
                    Path(scene), dict(params or {}), integrator, theirs, spp)
            except (OSError, ValueError, ET.ParseError) as e:  # ParseError is no ValueError
                raise RenderFailed(f"the harness could not write the scene for it: {e}") from None
            scene_file = Path(tmp) / "scene.xml"
            scene_file.write_text(text)
            for name, mesh in meshes.items():  # e.g. the OBJ files of a Nori scene's meshes, beside it
                (Path(tmp) / name).write_text(mesh)
            values = {"spp": str(spp), "integrator": theirs, "width": str(width), "height": str(height),
                      "threads": str(self._threads())}

            cancel, outer = threading.Event(), current_cancel()

            def call(k: int) -> tuple[np.ndarray, float]:
                with cancelled_by(outer):  # a render thread's cancel reaches the calls on threads of their own
                    return self._call(Path(tmp) / f"call{k}", scene_file, {**values, "seed": str(call_seed(seed, k))},
                                      shares[k], width, height, timeout, cancel)

            if self.file.jobs == 1:
                outcomes = [call(k) for k in range(len(shares))]  # the first failure ends the case at once
            else:
                with ThreadPoolExecutor(self.file.jobs) as pool:
                    futures = [pool.submit(call, k) for k in range(len(shares))]
                    try:
                        done, _ = wait(futures, return_when=FIRST_EXCEPTION)
                        failed = next((f for f in futures if f in done and f.exception() is not None), None)
                        if failed is not None:
                            raise failed.exception()
                        outcomes = [f.result() for f in futures]
                    except BaseException:
                        cancel.set()  # a failure or a Ctrl-C here ends the calls still running, at once
                        raise
        images = np.concatenate([images for images, _ in outcomes])
        seconds = {"render": float(sum(s for _, s in outcomes)), "total": time.perf_counter() - start}
        return RenderResult(self.name, str(scene), integrator, spp, seed, images, seconds, "independent")
