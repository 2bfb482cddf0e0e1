"""Null triples of real renders for the strategy check: Mitsuba's `direct` on its Cornell box (a small
rectangle light on the ceiling, diffuse walls and boxes) with emitter sampling alone (emitter_samples 1,
bsdf_samples 0: "ems"), BSDF sampling alone (0, 1: "mats") and both with MIS (1, 1: "mis"). Each triple is
three independent renders of IMAGE_BATCHES batches at one samples-per-pixel count, every batch with a seed of
its own, so any disagreement is a false alarm. Mitsuba runs in a child process (harness/engines/python_child.py).

    .venv/bin/python -m tools.strategy_renders --triples 200 --res 64 --spp 32

Writes results/calibration/strategies-cornell-<res>-<spp>.npz with keys "<triple>:<strategy>" ((K, H, W, 3)
float32), read by tools/strategy_calibration.py.
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from harness.comparison.strategies import STRATEGIES
from harness.engines.python_child import PythonChild
from harness.statistics.constants import IMAGE_BATCHES

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "results" / "calibration"
#: (emitter_samples, bsdf_samples) of Mitsuba's direct integrator per strategy.
SAMPLES = {"ems": (1, 0), "mats": (0, 1), "mis": (1, 1)}
#: Seconds a child may take for one triple (its first call imports Mitsuba and compiles its kernels).
CALL_SECONDS = 600.0


def path(res: int, spp: int, out: Path = OUT) -> Path:
    return out / f"strategies-cornell-{res}-{spp}.npz"


def render_triple(triple: int, res: int, spp: int, batches: int) -> dict[str, np.ndarray]:
    """In the child: one triple, each strategy's batches rendered with seeds of their own."""
    from harness.engines.mitsuba import DEFAULT_VARIANT, load_mitsuba

    mi = load_mitsuba(DEFAULT_VARIANT)
    scenes = _scenes(mi, res)
    out = {}
    for index, name in enumerate(STRATEGIES):
        seeds = [((triple * len(STRATEGIES) + index) * batches + b) for b in range(batches)]
        out[name] = np.stack([np.asarray(mi.render(scenes[name], spp=spp, seed=s), np.float32) for s in seeds])
    return out


_cache: dict[int, dict] = {}


def _scenes(mi, res: int) -> dict:
    if res not in _cache:
        scenes = {}
        for name, (emitter, bsdf) in SAMPLES.items():
            d = mi.cornell_box()
            d["sensor"]["film"].update(width=res, height=res)
            d["integrator"] = {"type": "direct", "emitter_samples": emitter, "bsdf_samples": bsdf}
            scenes[name] = mi.load_dict(d)
        _cache[res] = scenes
    return _cache[res]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--triples", type=int, default=200, help="null triples (default 200)")
    parser.add_argument("--res", type=int, default=64, help="image width and height (default 64)")
    parser.add_argument("--spp", type=int, default=32, help="samples per pixel of each batch (default 32)")
    parser.add_argument("--out", type=Path, default=OUT, help=f"folder of the .npz file (default {OUT})")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    child = PythonChild()
    data = {}
    try:
        for t in range(args.triples):
            triple = child.call("tools.strategy_renders:render_triple", t, args.res, args.spp, IMAGE_BATCHES,
                                timeout=CALL_SECONDS)
            data.update({f"{t}:{name}": batches for name, batches in triple.items()})
            if t % 20 == 19:
                print(f"{t + 1} of {args.triples} triples", flush=True)
    finally:
        child.close()
    target = path(args.res, args.spp, args.out)
    partial = target.with_name(target.stem + ".partial.npz")  # renamed once whole: a reader never sees half a file
    np.savez_compressed(partial, **data)
    partial.replace(target)
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
