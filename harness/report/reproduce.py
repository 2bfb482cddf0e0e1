"""The command that reproduces one case of a run: the case itself plus everything of the run that changes its
outcome (the engines, the scene file, the seed, the output folder and the environment variables that add
plugins or replace the renderer), so that pasting it gives the same verdict."""
from __future__ import annotations

import os
import shlex

#: Environment variables that change what a run renders or with what.
ENVIRONMENT = ("MCVAL_ENGINE_PATH", "MCVAL_INTEGRATOR_PATH", "MCVAL_RENDER", "MCVAL_RENDER_TIMEOUT")
#: Options whose value changes an outcome, and their defaults (left out when at them).
OPTIONS = (("engine", "--engine", "mcval"), ("reference", "--reference", "mitsuba"),
           ("variant", "--variant", "llvm_ad_rgb"), ("warp_library", "--warp-library", None),
           ("reference_image", "--reference-image", None), ("reference_spp", "--reference-spp", None),
           ("reference_noise", "--reference-noise", "stated"), ("resolution", "--resolution", None),
           ("out", "--out", "results"))


def invocation(args) -> dict:
    """What of a run's arguments and environment its reproduce lines repeat (JSON-ready)."""
    options = []
    for attribute, flag, default in OPTIONS:
        value = getattr(args, attribute, None)
        if value is not None and str(value) != str(default):
            options += [flag, str(value)]
    return {"options": options, "environment": {k: os.environ[k] for k in ENVIRONMENT if os.environ.get(k)}}


def reproduce_line(command: str, selection: list[str], seed: int, run: dict | None, scene_file: str = "") -> str:
    """`[VAR=value ...] mcval COMMAND SELECTION --seed S [--scene FILE] [options]`."""
    run = run or {"options": [], "environment": {}}
    words = ["mcval", command, *selection, "--seed", str(seed)]
    if scene_file:
        words += ["--scene", scene_file]
    env = [f"{k}={shlex.quote(v)}" for k, v in run["environment"].items()]
    return " ".join([*env, shlex.join(words + run["options"])])
