"""The warp checks' false-alarm rates, measured: every correct warp at many seeds, p-values counted.

For each warp of the matrix the seed-independent part of its statistical checks
(the cells, the expected probabilities, of its pdf and of its name's closed form)
is tabulated once, then each seed draws fresh samples from our warp and from
Mitsuba's and runs the chi-square goodness-of-fit tests (against the pdf, against
the closed form) and the homogeneity test exactly as the matrix does. The warps are
correct, so every rejection is a false alarm; `rates` states how often that
happens at each nominal level, with exact intervals. Each warp is one task on an
executor (harness.distributed), so a cluster runs the warps side by side.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.warps import checks as wc
from harness.statistics.calibration_rates import CALIBRATION_LEVELS, Rate, rates, uniformity_p
from harness.warps.domains import get_domain
from harness.engines.base import Engine
from harness.statistics.constants import WARP_SAMPLES
from harness.warps.bins import sample_quantum
from harness.warps.suite import WarpSpec, spec_seed
from harness.warps.targets import target_for

#: The warp checks that carry a p-value (the others are deterministic).
STATISTICAL_CHECKS = ("chi2", "samples_vs_target", "samples_vs_mitsuba")


@dataclass
class CheckCalibration:
    """Null p-values of one check (of one warp, or pooled over all), and the rates they give."""

    warp: str
    check: str
    p_values: np.ndarray
    rates: list[Rate]
    uniformity: float

    @property
    def within(self) -> bool:
        return all(r.within for r in self.rates)

    @property
    def sound(self) -> bool:
        """No rate lies above its nominal level beyond its interval."""
        return not any(r.liberal for r in self.rates)

    def to_json(self) -> dict:
        return {"warp": self.warp, "check": self.check, "comparisons": len(self.p_values),
                "false_alarm_rate": self.rates[-1].observed, "nominal_level": self.rates[-1].level,
                "rates": [r.to_json() for r in self.rates], "uniformity_p": self.uniformity,
                "within": self.within, "sound": self.sound}


@dataclass
class WarpCalibration:
    """Every warp and check, and each check pooled over the warps."""

    entries: list[CheckCalibration]
    pooled: list[CheckCalibration]
    seeds: int
    samples: int
    seconds: float
    failed: list[str] = field(default_factory=list)  # warps that gave no p-values, and why

    @property
    def within(self) -> bool:
        return all(e.within for e in self.entries + self.pooled)

    @property
    def sound(self) -> bool:
        """Every warp gave its p-values and no check raises more false alarms than its nominal level (a
        conservative one costs power only)."""
        return not self.failed and all(e.sound for e in self.entries + self.pooled)

    def to_json(self) -> dict:
        return {"seeds": self.seeds, "samples": self.samples, "seconds": self.seconds, "within": self.within,
                "pass": self.sound, "failed": self.failed,
                "levels": list(CALIBRATION_LEVELS), "pooled": [e.to_json() for e in self.pooled],
                "warps": [e.to_json() for e in self.entries]}


def null_p_values(spec: WarpSpec, tested: Engine, reference: Engine | None, seeds: range,
                  samples: int = WARP_SAMPLES, on_seed: Callable[[], None] | None = None) -> dict[str, np.ndarray]:
    """p-values of each statistical check of `spec` at every seed (the matrix's cells and tests)."""
    functions = tested.warp(spec.name, spec.alpha)
    ref = reference.warp(spec.name, spec.alpha) if reference is not None else None
    dom = get_domain(spec.domain)
    draws = lambda f, rng: wc.as_points(f.sample(rng.random((samples, 2))), samples, "sample")  # noqa: E731
    # The cells come from the pdf; the samples only say whether they are float32 (see warp_bins).
    pilot = [draws(f, np.random.default_rng([spec_seed(spec, 0), 1])) for f in (functions, ref) if f is not None]
    quantum = sample_quantum(*pilot)
    bins, cells = wc.equal_probability_cells(dom, functions.pdf, samples, quantum)
    probabilities = cells.values
    target = target_for(spec.name, spec.alpha)
    if target is not None:
        target_bins, target_probabilities = target.cells(samples, quantum)
    out: dict[str, list[float]] = ({"chi2": []} | ({"samples_vs_target": []} if target is not None else {})
                                   | ({"samples_vs_mitsuba": []} if ref is not None else {}))
    for seed in seeds:
        rng = np.random.default_rng(spec_seed(spec, seed))
        points = draws(functions, rng)
        inside = dom.inside(points)
        param = dom.to_param(points[inside])
        observed = wc.histogram(dom, points[inside], bins, param)
        outside = int(np.count_nonzero(~inside))
        out["chi2"].append(wc.chi2_check(observed, probabilities, outside).p_value)
        if target is not None:
            in_target = observed if target_bins.same_edges(bins) else wc.histogram(dom, points[inside], target_bins,
                                                                                   param)
            out["samples_vs_target"].append(wc.chi2_check(in_target, target_probabilities, outside).p_value)
        if ref is not None:
            ref_points = draws(ref, rng)
            ref_observed = wc.histogram(dom, ref_points[dom.contains(ref_points)], bins)
            out["samples_vs_mitsuba"].append(wc.homogeneity_check(observed, ref_observed).p_value)
        if on_seed:
            on_seed()
    return {k: np.asarray(v) for k, v in out.items()}


def calibrate_warps(tested: Engine, reference: Engine | None, specs: list[WarpSpec], seeds: int = 200,
                    samples: int = WARP_SAMPLES, executor: Executor | None = None,
                    on_status: Callable[[Status], None] | None = None) -> WarpCalibration:
    """Every spec at `seeds` seeds, one task per spec on `executor` (serial by default); rates per warp and
    check, and pooled per check over the warps."""
    executor = executor or SerialExecutor()
    start = time.perf_counter()
    outcomes = executor.run([Task(f"warp {spec.key}", null_p_values, (spec, tested, reference, range(seeds), samples))
                             for spec in specs], on_status)
    p_values = {spec.key: o.value for spec, o in zip(specs, outcomes) if o.ok}
    failed = [f"{spec.key}: {o.error}" for spec, o in zip(specs, outcomes) if not o.ok]
    checks = [c for c in STATISTICAL_CHECKS if any(c in v for v in p_values.values())]
    intervals = (sum(len(v) for v in p_values.values()) + len(checks)) * len(CALIBRATION_LEVELS)

    def entry(warp: str, check: str, p: np.ndarray) -> CheckCalibration:
        return CheckCalibration(warp, check, p, rates(p, intervals), uniformity_p(p))

    entries = [entry(key, check, p) for key, v in p_values.items() for check, p in v.items()]
    pooled = [entry("all warps", check, np.concatenate([v[check] for v in p_values.values() if check in v]))
              for check in checks]
    return WarpCalibration(entries, pooled, seeds, samples, time.perf_counter() - start, failed)
