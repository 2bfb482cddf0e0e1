"""The side-by-side render throughput table alone: ours and Mitsuba in one process on the four cases of
harness/bench/throughput.py, interleaved run by run.

    .venv/bin/python -m tools.throughput [runs] [sampler]
"""
from __future__ import annotations

from harness.bench.throughput import CASES, MITSUBA, MITSUBA_SAMPLER, OURS, WORKER, Throughput, measure


def table(results: list[Throughput]) -> str:
    """The measurements as a plain-text table: seconds, Mitsuba over ours, Msamples/s and Mrays/s of each."""
    lines = [f"{'case':<30} {'ours s':>7} {'Mitsuba s':>9} {'Mitsuba/ours':>12} {'Msamples/s ours':>15} "
             f"{'Mitsuba':>8} {'Mrays/s ours':>12} {'Mitsuba':>8} {'worker s':>8} {'Mitsuba/worker':>14}"]
    for r in results:
        j = r.to_json()
        lines.append(f"{f'{r.scene}:{r.integrator} {r.resolution}² {r.spp} spp':<30} {r.median(OURS):7.3f} "
                     f"{r.median(MITSUBA):9.3f} {r.ratio():12.2f} "
                     + (f"(Mitsuba {r.mitsuba_spp} spp) " if r.mitsuba_spp != r.spp else "") +
                     f"{j['samples_per_second'][OURS] / 1e6:15.1f} {j['samples_per_second'][MITSUBA] / 1e6:8.1f} "
                     f"{j['rays_per_second'][OURS] / 1e6:12.1f} {j['rays_per_second'][MITSUBA] / 1e6:8.1f} "
                     f"{r.median(WORKER):8.3f} {r.ratio(WORKER):14.2f}")
    return "\n".join(lines)


if __name__ == "__main__":
    import sys
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    sampler = sys.argv[2] if len(sys.argv) > 2 else "independent"
    print(table([measure(*case, runs=runs, sampler=sampler) for case in CASES]))
    print(f"Render time only, each timed render after a pause and an untimed one of the same engine; medians of {runs} runs; "
          "Mitsuba/ours per sample, the median of the per-round ratios; worker: ours in its render --serve worker, as "
          "images and validate run it (wall clock less load and BVH); "
          f"sampler {sampler} "
          f"(Mitsuba: {MITSUBA_SAMPLER.get(sampler, sampler)}); rays/s from our ray count for both.")
