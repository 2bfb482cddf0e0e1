"""How often the strategy check (harness/comparison/strategies.py) calls a correct renderer anything but
"agree", and the smallest bias of one strategy it names 90 % of the time.

    .venv/bin/python -m tools.strategy_calibration                      # synthetic triples, then every
                                                                         # results/calibration/strategies-*.npz
    .venv/bin/python -m tools.strategy_calibration --triples 200 --power-replications 100

Null triples are synthetic (tools/strategy_triples.py, 32x32, 8 batches of 32 samples) or Mitsuba's renders
(tools/strategy_renders.py). For each nominal level: the triples with any rejection (the false-alarm rate, with
its Clopper-Pearson interval, simultaneous at 95 % over the levels), and those where a strategy was named.
Power: each strategy's batches scaled by 1 + b (the whole image; then by the twins' shapes,
tools/strategy_triples.py), b on a grid, over the first
`--power-replications` null triples, at the suite's level (SIGNIFICANCE): the fraction where that strategy is
named, and the smallest b named 90 % of the time.
"""
from __future__ import annotations

import argparse
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from harness.comparison.strategies import STRATEGIES, compare_strategies
from harness.statistics.calibration_rates import CALIBRATION_LEVELS, rates
from harness.statistics.constants import POWER_TARGET, SIGNIFICANCE
from tools.strategy_renders import OUT
from tools.strategy_triples import AREA_MEASURE, DOUBLE_COUNT, UNIFORM, null_triple, planted

Triple = dict[str, np.ndarray]
#: The planted biases: each strategy's whole image scaled alike, then the twins' shapes (a light pdf left in area
#: measure, MIS weights that double count where both pdfs are alike).
PLANTS = (("ems", UNIFORM), ("mats", UNIFORM), ("mis", UNIFORM), ("ems", AREA_MEASURE), ("mis", DOUBLE_COUNT))
#: Relative biases tried for the power figures.
BIASES = (0.005, 0.01, 0.015, 0.02, 0.025, 0.03, 0.035, 0.04, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.5)
SYNTHETIC_SPP = 32


def synthetic(count: int, size: int = 32) -> Iterator[Triple]:
    for i in range(count):
        yield null_triple(np.random.default_rng(10_000 + i), size, spp=SYNTHETIC_SPP)


def stored(path: Path, count: int) -> Iterator[Triple]:
    with np.load(path) as data:
        triples = sorted({int(key.split(":")[0]) for key in data.files})[:count]
        for t in triples:
            yield {name: data[f"{t}:{name}"] for name in STRATEGIES}


def null_rates(triples: list[Triple], spp: int) -> list[str]:
    lines = []
    for level in CALIBRATION_LEVELS:
        checks = [compare_strategies(t, alpha=level, spp=spp, power=False) for t in triples]
        alarms = np.array([0.0 if c.disagree else 1.0 for c in checks])  # as p-values: 0 rejects
        (rate,) = rates(alarms, len(CALIBRATION_LEVELS), (level,))
        named = Counter(c.odd for c in checks if c.odd)
        lines.append(f"  level {level:<5g} false alarms {rate.rejections:3d}/{rate.count} = {rate.observed:.3f} "
                     f"[{rate.low:.3f}, {rate.high:.3f}] {rate.verdict}; named: "
                     + (", ".join(f"{k} {v}" for k, v in sorted(named.items())) or "none"))
    return lines


def power(triples: list[Triple], spp: int, biases: tuple[float, ...] | None = None) -> list[str]:
    biases = BIASES if biases is None else biases
    lines = []
    for strategy, shape in PLANTS:
        found = []
        for b in biases:
            named = sum(compare_strategies(planted(t, strategy, b, shape), alpha=SIGNIFICANCE, spp=spp,
                                           power=False).odd == strategy for t in triples)
            found.append(named / len(triples))
            if found[-1] >= POWER_TARGET:
                break
        curve = ", ".join(f"{b:g}: {f:.2f}" for b, f in zip(biases, found))
        smallest = next((f"{b:g}" for b, f in zip(biases, found) if f >= POWER_TARGET), f"> {biases[-1]:g}")
        lines.append(f"  {strategy:<4} x (1 + b {shape.__name__.removesuffix('_shape')}) named {POWER_TARGET:.0%} "
                     f"of the time from b = {smallest} ({curve})")
    return lines


def report(name: str, triples: list[Triple], spp: int, replications: int,
           biases: tuple[float, ...] | None = None) -> None:
    k, h, w, _ = triples[0]["ems"].shape
    print(f"{name}: {len(triples)} null triples, {k} batches of {spp} samples, {w}x{h}", flush=True)
    for line in null_rates(triples, spp):
        print(line, flush=True)
    print(f"  power at level {SIGNIFICANCE:g} over {min(replications, len(triples))} triples:")
    for line in power(triples[:replications], spp, biases):
        print(line, flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="*", type=Path, help="triples of tools/strategy_renders.py (default: "
                        f"every {OUT}/strategies-*.npz)")
    parser.add_argument("--triples", type=int, default=200, help="null triples per set (default 200)")
    parser.add_argument("--power-replications", type=int, default=100, help="triples per planted bias (default 100)")
    parser.add_argument("--no-synthetic", action="store_true", help="measure the stored renders only")
    parser.add_argument("--biases", type=lambda text: tuple(map(float, text.split(","))), default=BIASES,
                        help="relative biases tried, comma-separated, ascending (default: a grid from 0.005 to 0.5)")
    args = parser.parse_args()
    if not args.no_synthetic:
        report("synthetic", list(synthetic(args.triples)), SYNTHETIC_SPP, args.power_replications, args.biases)
    stored_sets = [p for p in sorted(OUT.glob("strategies-*.npz")) if not p.name.endswith(".partial.npz")]
    for path in args.files or stored_sets:
        spp = int(path.stem.rsplit("-", 1)[1])
        report(path.name, list(stored(path, args.triples)), spp, args.power_replications, args.biases)


if __name__ == "__main__":
    main()
