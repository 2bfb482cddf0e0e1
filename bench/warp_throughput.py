"""Warp throughput of both engines, like for like: the same warp on the same N float32 uniforms, each engine in its
own containers (mcval: an (N, 2) numpy array; Mitsuba llvm_ad_rgb: a Point2f), in one process, timed in
interleaved pairs (mcval, Mitsuba, mcval, ...; each timed call after an untimed one of its own), the ratio taken per
pair and the median of the ratios quoted, so that the machine's drift cancels.

    .venv/bin/python bench/warp_throughput.py [--sizes 20 24] [--pairs 15] [--json results/warp_throughput.json]

`make bench` runs it. It prints the table and writes the figures as JSON.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # the harness, when run as a script

from harness.engines.registry import make_engine  # noqa: E402
from harness.warps.checks import measure_rates_interleaved  # noqa: E402
from harness.warps.suite import SUITE  # noqa: E402


def measure(sizes: list[int], pairs: int) -> list[dict]:
    mcval, mitsuba = make_engine("mcval"), make_engine("mitsuba")
    rows = []
    for spec in SUITE:
        mine, theirs = mcval.warp(spec.name, spec.alpha), mitsuba.warp(spec.name, spec.alpha)
        if theirs is None:  # Mitsuba has no such warp (the uniform square)
            continue
        for log2n in sizes:
            n = 1 << log2n
            rate, ref_rate, ratio = measure_rates_interleaved(mine.native_run(n), theirs.native_run(n), n, pairs)
            rows.append({"warp": spec.key, "n": n, "mcval_samples_per_second": rate,
                         "mitsuba_samples_per_second": ref_rate, "mcval_over_mitsuba": ratio})
            print(f"{spec.key:22s} 2^{log2n:<3d} {rate / 1e6:9.0f} {ref_rate / 1e6:9.0f} {ratio:7.2f}", flush=True)
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[20, 24], help="log2 of N (default 20 24)")
    parser.add_argument("--pairs", type=int, default=15, help="interleaved pairs per warp and size (default 15)")
    parser.add_argument("--json", type=Path, default=Path("results/warp_throughput.json"), help="where to write the figures")
    args = parser.parse_args(argv)
    print(f"{'warp':22s} {'N':5s} {'mcval M/s':>9s} {'mi M/s':>9s} {'mcval/mi':>7s}   (medians of {args.pairs} interleaved pairs)")
    rows = measure(args.sizes, args.pairs)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.json.with_suffix(".tmp")
    tmp.write_text(json.dumps({"method": "interleaved pairs, median of per-pair ratios", "pairs": args.pairs,
                               "warps": rows}, indent=1))
    tmp.replace(args.json)
    print(f"Figures: {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
