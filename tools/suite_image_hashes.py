"""The SHA-256 of every image-suite case of the given integrators, rendered by the `render` binary at a fixed
seed and sample count: one `scene integrator sha256` line each, over the pixels of every layer of the EXR
(its mean and variance; not its header, whose timings change from run to run). Two renderers whose lines agree draw the same
bits on every suite scene (a refactoring of the renderer's emitter or BSDF model must keep them).

    .venv/bin/python -m tools.suite_image_hashes --render build/render > before.txt
    ... change the renderer, rebuild ...
    .venv/bin/python -m tools.suite_image_hashes --render build/render | diff before.txt -
"""
from __future__ import annotations

import argparse
import hashlib
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from harness.exr import read_layers
from harness.images.suite import select_cases

DEFAULT_INTEGRATORS = ("normals", "simple", "ao")


def image_hash(render: Path, scene: Path, integrator: str, spp: int, seed: int, out: Path) -> str:
    """The SHA-256 of the layers of the EXR that `render` writes for one scene and integrator, by name."""
    subprocess.run([str(render), str(scene), "--integrator", integrator, "--spp", str(spp), "--seed", str(seed),
                    "-o", str(out)], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    layers, _ = read_layers(out)
    digest = hashlib.sha256()
    for name in sorted(layers):
        digest.update(name.encode() + b"\0")
        digest.update(np.ascontiguousarray(layers[name], dtype="<f4").tobytes())
    return digest.hexdigest()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--render", type=Path, default=Path("build/render"), help="the render binary")
    parser.add_argument("--integrators", nargs="+", default=list(DEFAULT_INTEGRATORS))
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel (default 16)")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as folder:
        for case in select_cases(None, integrators=args.integrators):
            digest = image_hash(args.render, case.path, case.integrator, args.spp, args.seed,
                                Path(folder) / "image.exr")
            print(f"{case.scene} {case.integrator} {digest}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
