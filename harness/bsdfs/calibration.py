"""The BSDF checks' false-alarm rates and power, measured (`calibrate --bsdfs`).

Null rows: correct BSDFs (a library's, ours by default, each against Mitsuba's plugin of the same name) at one
incident angle each, run at many seeds with every check exactly as the matrix runs it (harness/bsdfs/evaluate.py).
Every rejection is a false alarm: a statistical check's p-values give its rate at each nominal level with an exact
interval; a deterministic check (the weight, the reciprocity, ...) must never fail.

The energy check is one-sided at an albedo of 1, and a BSDF that loses energy sits below that edge, where its rate
can only be low; so one more null row sits on the edge (harness/bsdfs/boundary.py: weights of mean exactly 1).
Power, on the same BSDF with a defect of the size the checks state: its albedo raised by the excess the energy
check says it finds 90 % of the time, as large a share of its samples moved between the halves of its mass as the
sampling check says it finds 90 % of the time, and its weights off by twice the weight check's tolerance."""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from harness.bsdfs.boundary import uniform_lambert
from harness.bsdfs.checks import POWER, WEIGHT_TOLERANCE, draw, energy_check, incident, weight_check
from harness.bsdfs.evaluate import STATISTICAL, check_bsdf_at, sampling_at
from harness.engines.base import BsdfFunctions
from harness.engines.python_child import ChildRaised
from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.statistics.calibration_rates import (CALIBRATION_CONFIDENCE, CALIBRATION_LEVELS, clopper_pearson,
                                                  rates, uniformity_p)
from harness.warps.calibration import CheckCalibration

#: The null rows of a library's BSDFs ("SPEC@DEGREES"): a smooth lobe, rough lobes of both distributions with
#: and without visible sampling, a coated one (a delta lobe over a diffuse base), and a glass (delta lobes only).
NULL_ROWS = ("diffuse@30", "plastic@30", "dielectric@60",
             "roughconductor:alpha=0.5,ggx=1,sample_visible=1@60", "roughconductor:alpha=0.2,ggx=0,sample_visible=0@0")
#: The row on the energy check's edge (harness/bsdfs/boundary.py), run with every library.
BOUNDARY_ROW = "uniform_lambert@30"
#: Per-test levels at which the planted defects' detection is measured: the loosest calibrated level and one as
#: strict as a default matrix's Sidak split (0.01 over a few hundred tests).
POWER_LEVELS = (CALIBRATION_LEVELS[-1], 1e-4)
#: The weight defect planted: weights off by this factor (twice the tolerance).
WEIGHT_DEFECT = 1.0 + 2.0 * WEIGHT_TOLERANCE
#: Seeds of one row per task: a cluster shares a row's seeds out, and progress moves within a row.
SEEDS_PER_TASK = 25


def parse_row(text: str) -> tuple[str, float]:
    """"roughconductor:alpha=0.1@60" -> ("roughconductor:alpha=0.1", 60.0); ValueError saying what was expected."""
    spec, at, angle = text.rpartition("@")
    try:
        theta = float(angle)
    except ValueError:
        theta = None
    if not at or not spec or theta is None or not 0.0 <= theta <= 180.0:
        raise ValueError(f"--bsdf {text}: expected NAME[:p=v,...]@DEGREES (e.g. roughconductor:alpha=0.1@60, "
                         "degrees from 0 to 180)")
    return spec, theta


#: What gives a null row's BSDF and its reference (None: none) from the row's spec text: picklable (a cluster's
#: workers call it), and from outside the suites (harness/commands/bsdf_section.py), which alone know engines.
FunctionsOf = Callable[[str], tuple[BsdfFunctions, BsdfFunctions | None]]


def null_row(functions_of: FunctionsOf, row: str, seeds: range, samples: int, base_seed: int) -> dict:
    """One null row at every seed: the p-values of its statistical checks, and how often each deterministic check
    failed (with the first failure's summary). A statistical check that gives no p-value is a failure too."""
    spec_text, theta = parse_row(row)
    boundary = spec_text == BOUNDARY_ROW.partition("@")[0]
    try:
        bsdf, reference = (uniform_lambert(), None) if boundary else functions_of(spec_text)
        return _null_runs(bsdf, reference, theta, seeds, samples, base_seed)
    except (ChildRaised, RuntimeError, ValueError) as e:  # crashed or hung (ChildFailed), refused, lacks the BSDF
        return {"label": row, "error": f"seeds {seeds.start}-{seeds.stop - 1}: {getattr(e, 'reason', e)}"}


def _null_runs(bsdf: BsdfFunctions, reference: BsdfFunctions | None, theta: float, seeds: range, samples: int,
               base_seed: int) -> dict:
    p_values: dict[str, list[float]] = {}
    failures: dict[str, int] = {}
    examples: dict[str, str] = {}
    runs: dict[str, int] = {}
    for s in seeds:
        results = check_bsdf_at(bsdf, incident(theta), samples, base_seed + 2 * s, CALIBRATION_LEVELS[-1], reference)
        for name, check in results.items():
            if name in STATISTICAL and check.p_value is not None and check.hard_failure is None:
                p_values.setdefault(name, []).append(float(check.p_value))
                continue
            runs[name] = runs.get(name, 0) + 1
            if not check.passed:
                failures[name] = failures.get(name, 0) + 1
                examples.setdefault(name, f"seed {s}: {check.summary}")
    return {"label": f"{bsdf.label} at {theta:g} degrees", "p_values": p_values, "runs": runs, "failures": failures,
            "examples": examples}


def energy_power(level: float, seeds: range, samples: int, base_seed: int) -> dict:
    """The excess the energy check states it finds POWER of the time at `level`, planted (the boundary BSDF with
    its albedo raised by it), and how often the check finds it."""
    wi = incident(30.0)
    pilot = energy_check(draw(uniform_lambert(), wi, samples, base_seed), level)
    excess = float(pilot.details["detectable_excess"])
    planted = uniform_lambert(1.0 + excess)
    found = sum(energy_check(draw(planted, wi, samples, base_seed + 1 + s), level).p_value < level for s in seeds)
    return {"check": "energy", "defect": f"albedo 1 + {excess:.3g}", "level": level, "stated_power": POWER,
            "runs": len(seeds), "found": int(found)}


def sampling_power(level: float, seeds: range, samples: int, base_seed: int) -> dict:
    """The share of samples moved between the halves of the mass that the sampling check states it finds POWER of
    the time at `level`, planted (the boundary BSDF with as many samples moved), and how often the check finds it."""
    wi = incident(30.0)
    moved = sampling_at(uniform_lambert(), wi, samples, base_seed, level)[1].details.get("detects_mass_moved")
    figure = {"check": "sampling", "level": level, "stated_power": POWER}
    if moved is None:  # nothing stated: the figure cannot hold
        return figure | {"defect": "none stated", "runs": 0, "found": 0}
    planted = uniform_lambert(moved=moved)
    found = sum(sampling_at(planted, wi, samples, base_seed + 1 + s, level)[1].p_value < level for s in seeds)
    return figure | {"defect": f"{moved:.3g} of the samples moved to the upper half of the mass", "runs": len(seeds),
                     "found": int(found)}


def weight_power(seeds: range, samples: int, base_seed: int) -> dict:
    """Weights off by WEIGHT_DEFECT (twice the tolerance) planted, and how often the weight check finds them."""
    planted, wi = uniform_lambert(weight_factor=WEIGHT_DEFECT), incident(30.0)
    found = sum(not weight_check(planted, draw(planted, wi, samples, base_seed + s)).passed for s in seeds)
    return {"check": "weight", "defect": f"weights x {WEIGHT_DEFECT:g}", "level": None, "stated_power": 1.0,
            "runs": len(seeds), "found": int(found)}


def _merge(parts: list[dict]) -> list[dict]:
    """The chunks of each row (null_row's results over consecutive seeds) as one result per row."""
    rows: dict[str, dict] = {}
    for part in parts:
        row = rows.setdefault(part["label"], {"label": part["label"], "p_values": {}, "runs": {}, "failures": {},
                                              "examples": {}})
        for check, p in part["p_values"].items():
            row["p_values"].setdefault(check, []).extend(p)
        for key in ("runs", "failures"):
            for check, n in part[key].items():
                row[key][check] = row[key].get(check, 0) + n
        for check, text in part["examples"].items():
            row["examples"].setdefault(check, text)
    return list(rows.values())


@dataclass
class DeterministicCalibration:
    """A check without a p-value on one row: how often it failed in its null runs (never, for a sound one)."""

    row: str
    check: str
    runs: int
    failures: int
    example: str | None
    low: float
    high: float

    def to_json(self) -> dict:
        return {"bsdf": self.row, "check": self.check, "runs": self.runs, "failures": self.failures,
                "false_alarm_rate": self.failures / self.runs if self.runs else None, "interval": [self.low, self.high],
                "example": self.example}


@dataclass
class PowerFigure:
    """A planted defect of the stated size: how often its check found it, beside the power the check states."""

    check: str
    defect: str
    level: float | None
    stated: float
    runs: int
    found: int
    low: float
    high: float

    @property
    def holds(self) -> bool:
        """The stated power is not above the measured rate's interval."""
        return self.runs > 0 and self.high >= self.stated

    def to_json(self) -> dict:
        return {"check": self.check, "defect": self.defect, "level": self.level, "stated_power": self.stated,
                "runs": self.runs, "found": self.found, "power": self.found / self.runs if self.runs else None,
                "interval": [self.low, self.high], "holds": self.holds}


@dataclass
class BsdfCalibration:
    """Every null row's checks, each statistical check pooled over the rows, and the planted defects' power."""

    entries: list[CheckCalibration]
    pooled: list[CheckCalibration]
    deterministic: list[DeterministicCalibration]
    power: list[PowerFigure]
    seeds: int
    samples: int
    seconds: float
    failed: list[str] = field(default_factory=list)  # rows that gave no results, and why
    degenerate: list[str] = field(default_factory=list)  # "row: check" whose p-value was 1 at every seed

    @property
    def within(self) -> bool:
        return all(e.within for e in self.entries + self.pooled)

    @property
    def sound(self) -> bool:
        """Every row ran; no statistical check raises more false alarms than it says, no deterministic check
        failed a correct BSDF, and every planted defect was found as often as stated."""
        return (not self.failed and all(e.sound for e in self.entries + self.pooled)
                and not any(d.failures for d in self.deterministic) and all(p.holds for p in self.power))

    @property
    def null_runs(self) -> int:
        return sum(len(e.p_values) for e in self.entries) + sum(d.runs for d in self.deterministic)

    def to_json(self) -> dict:
        return {"seeds": self.seeds, "samples": self.samples, "seconds": self.seconds, "within": self.within,
                "pass": self.sound, "failed": self.failed, "degenerate": self.degenerate, "levels": list(CALIBRATION_LEVELS),
                "pooled": [_bsdf_json(e) for e in self.pooled], "checks": [_bsdf_json(e) for e in self.entries],
                "deterministic": [d.to_json() for d in self.deterministic], "power": [p.to_json() for p in self.power]}


def calibrate_bsdfs(functions_of: FunctionsOf, rows: list[str], seeds: int, samples: int,
                    executor: Executor | None = None,
                    on_status: Callable[[Status], None] | None = None) -> BsdfCalibration:
    """Every null row ("SPEC@DEGREES" as NULL_ROWS, its BSDFs from `functions_of`, and BOUNDARY_ROW) at `seeds`
    seeds and the planted defects at as many, a task per SEEDS_PER_TASK seeds of a row on `executor` (serial by
    default)."""
    executor = executor or SerialExecutor()
    start = time.perf_counter()
    rows = list(dict.fromkeys([*rows, BOUNDARY_ROW]))
    chunks = [range(a, min(a + SEEDS_PER_TASK, seeds)) for a in range(0, seeds, SEEDS_PER_TASK)]
    tasks = [Task(f"bsdf {row} seeds {c.start}-{c.stop - 1}", null_row,
                  (functions_of, row, c, samples, 1_000_003 * (i + 1))) for i, row in enumerate(rows) for c in chunks]
    row_tasks = len(tasks)
    if seeds:  # the planted defects, at as many seeds
        tasks += [Task(f"energy power at {level:g}", energy_power, (level, range(seeds), samples, 7_000_001 * (i + 1)))
                  for i, level in enumerate(POWER_LEVELS)]
        tasks += [Task(f"sampling power at {level:g}", sampling_power, (level, range(seeds), samples,
                                                                         5_000_011 * (i + 1)))
                  for i, level in enumerate(POWER_LEVELS)]
        tasks.append(Task("weight power", weight_power, (range(seeds), samples, 9_000_001)))
    outcomes = executor.run(tasks, on_status)
    failed = [f"{task.key}: {o.error}" for task, o in zip(tasks, outcomes) if not o.ok]
    parts = [o.value for o in outcomes[:row_tasks] if o.ok]
    failed += [f"{p['label']}: {p['error']}" for p in parts if "error" in p]
    done = _merge([p for p in parts if "error" not in p])
    planted = [o.value for o in outcomes[row_tasks:] if o.ok]
    every = [(r["label"], c, np.asarray(p)) for r in done for c, p in r["p_values"].items()]
    # p = 1 at every seed: nothing random was tested (a glass's sampling without a density, the energy of a BSDF
    # far below albedo 1); such a row says nothing of the rate and would dilute the pooled one.
    degenerate = [f"{row}: {c}" for row, c, p in every if len(p) and np.all(p >= 1.0 - 1e-12)]
    statistical = [(row, c, p) for row, c, p in every if f"{row}: {c}" not in degenerate]
    checks = [c for c in STATISTICAL if any(name == c for _, name, _ in statistical)]
    deterministic = [(r["label"], c, n, r["failures"].get(c, 0), r["examples"].get(c))
                     for r in done for c, n in r["runs"].items()]
    # Every interval of the calibration holds at once with CALIBRATION_CONFIDENCE (Bonferroni).
    intervals = (len(statistical) + len(checks)) * len(CALIBRATION_LEVELS) + len(deterministic) + len(planted)
    each = 1.0 - (1.0 - CALIBRATION_CONFIDENCE) / max(intervals, 1)

    def entry(row: str, check: str, p: np.ndarray) -> CheckCalibration:
        return CheckCalibration(row, check, p, rates(p, intervals), uniformity_p(p))

    pooled = [entry("all rows", c, np.concatenate([p for _, name, p in statistical if name == c])) for c in checks]
    return BsdfCalibration(
        [entry(*s) for s in statistical], pooled,
        [DeterministicCalibration(row, c, n, k, ex, *clopper_pearson(k, n, each)) for row, c, n, k, ex in deterministic],
        [PowerFigure(p["check"], p["defect"], p["level"], p["stated_power"], p["runs"], p["found"],
                     *clopper_pearson(p["found"], p["runs"], each)) for p in planted],
        seeds, samples, time.perf_counter() - start, failed, degenerate)


def _bsdf_json(e: CheckCalibration) -> dict:
    """A row's figure as JSON, naming its row "bsdf"."""
    out = e.to_json()
    return {"bsdf": out.pop("warp"), **out}
