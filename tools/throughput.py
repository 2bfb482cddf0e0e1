"""The side-by-side render throughput table alone: the tested engine (in process and in its worker) and the reference as shipped
(or `mitsuba-robust`: with Embree's robust intersections, as ours) on the cases of harness/bench/throughput.py,
interleaved run by run.

    .venv/bin/python -m tools.throughput [runs] [sampler] [reference engine, default mitsuba-native]
"""
from __future__ import annotations

from harness.bench.throughput import CASES, REFERENCE, TESTED, WORKER, Throughput, measure


def table(results: list[Throughput]) -> str:
    """The measurements as a plain-text table: seconds, reference over tested, Msamples/s and Mrays/s of each."""
    lines = [f"{'case':<30} {'tested s':>8} {'ref. s':>7} {'ref./tested':>11} {'Msamples/s tested':>17} "
             f"{'ref.':>6} {'Mrays/s tested':>14} {'ref.':>6} {'worker s':>8} {'ref./worker':>11}"]
    for r in results:
        j = r.to_json()
        rays = j.get("rays_per_second", {TESTED: float("nan"), REFERENCE: float("nan")})
        worker = f"{r.median(WORKER):8.3f} {r.ratio(WORKER):11.2f}" if WORKER in r.seconds else ""
        lines.append(f"{f'{r.scene}:{r.integrator} {r.resolution}² {r.spp} spp':<30} {r.median(TESTED):8.3f} "
                     f"{r.median(REFERENCE):7.3f} {r.ratio():11.2f} "
                     f"{j['samples_per_second'][TESTED] / 1e6:17.1f} {j['samples_per_second'][REFERENCE] / 1e6:6.1f} "
                     f"{rays[TESTED] / 1e6:14.1f} {rays[REFERENCE] / 1e6:6.1f} {worker}")
    return "\n".join(lines)


if __name__ == "__main__":
    import sys

    from harness.engines.mitsuba_scene import MITSUBA_SAMPLER
    from harness.engines.registry import make_engine
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    sampler = sys.argv[2] if len(sys.argv) > 2 else "independent"
    tested, worker = make_engine("mcval", sampler=sampler, in_process=True), make_engine("mcval", sampler=sampler)
    reference_name = sys.argv[3] if len(sys.argv) > 3 else "mitsuba-native"
    reference = make_engine(reference_name, sampler=MITSUBA_SAMPLER.get(sampler, sampler))
    print(table([measure(*case, tested, reference, worker, runs=runs, sampler=sampler) for case in CASES]))
    print(f"Render time only, each timed render after a pause and an untimed one of the same engine; medians of {runs} "
          "runs; reference/tested: the median of the per-round ratios; worker: the tested engine in its render --serve worker, as "
          f"images and validate run it (wall clock less load and BVH); sampler {sampler} "
          f"(Mitsuba: {MITSUBA_SAMPLER.get(sampler, sampler)}); reference {reference.label}; rays/s from our ray "
          "count for both.")
