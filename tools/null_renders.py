"""Null render pairs for measuring the image comparison's calibration: two independent runs of our
renderer on one scene, shaped like a validation (a test side of IMAGE_BATCHES batches, a reference side
of REFERENCE_BATCHES), both at the test's samples per pixel by default, so any rejection is a false
alarm. (At different sample counts a stratified sampler's batches are not the same estimator: at a
shadow edge 8 batches of 32 samples can all take the lower of two values 3 % apart, which the
comparison rightly calls a difference from 256-sample batches.)

    .venv/bin/python -m tools.null_renders --pairs 200 --res 64 crevice:ao grazing_light:simple

Writes results/calibration/nulls-<scene>-<integrator>.npz with keys "<scene>:<integrator>:<pair>:a|b"
(read by tools/image_calibration.py). Each pair has its own seeds, so pairs are independent.
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from rich.progress import Progress

import mcval_renderer
from harness.images.suite import TESTED_SPP
from harness.images.references import REFERENCE_BATCHES
from harness.statistics.constants import IMAGE_BATCHES

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "results" / "calibration"


def render_pair(scene: Path, integrator: str, pair: int, res: int,
                reference_spp: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    params = {"res": str(res)}
    seed = 100_000 + 2 * pair

    def side(spp: int, batches: int, s: int) -> np.ndarray:
        out = mcval_renderer.render(str(scene), spp=spp, seed=s, batches=batches, integrator=integrator, params=params)
        return np.asarray(out["batches"], np.float32)

    return (side(TESTED_SPP[integrator], IMAGE_BATCHES, seed),
            side(reference_spp or TESTED_SPP[integrator], REFERENCE_BATCHES, seed + 1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("cases", nargs="+", help="scene:integrator, the scene a file of scenes/")
    parser.add_argument("--pairs", type=int, default=200, help="null pairs per case (default 200)")
    parser.add_argument("--res", type=int, default=64, help="image width and height (default 64)")
    parser.add_argument("--reference-spp", type=int, help="samples per pixel of the reference side (default: "
                        "the test's)")
    parser.add_argument("--out", type=Path, default=OUT, help=f"folder of the .npz files (default {OUT})")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    with Progress() as progress:
        for case in args.cases:
            scene, integrator = case.split(":")
            task = progress.add_task(case, total=args.pairs)
            data = {}
            for pair in range(args.pairs):
                a, b = render_pair(ROOT / "scenes" / f"{scene}.xml", integrator, pair, args.res, args.reference_spp)
                data[f"{case}:{pair}:a"], data[f"{case}:{pair}:b"] = a, b
                progress.advance(task)
            target = args.out / f"nulls-{scene}-{integrator}.npz"
            partial = target.with_suffix(".partial.npz")
            np.savez(partial, **data)
            partial.replace(target)


if __name__ == "__main__":
    main()
