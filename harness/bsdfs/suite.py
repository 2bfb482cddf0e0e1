"""The BSDF matrix: every BSDF asked for (at its parameter values) at every incident angle, all its checks
(harness/bsdfs/evaluate.py) decided at one per-test level, the run's family-wise level split over every
statistical check of the matrix (Sidak)."""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from harness.bsdfs.checks import draw, incident
from harness.bsdfs.evaluate import OWN_STATISTICAL, REFERENCE_STATISTICAL, check_bsdf_at
from harness.engines.base import BsdfFunctions
from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.python_child import ChildFailed
from harness.statistics.constants import sidak_level
from harness.warps.check_result import CheckResult

#: Incident angles from the normal, in degrees: normal, oblique and grazing incidence.
ANGLES = (0.0, 30.0, 60.0, 80.0, 89.0)
#: Samples per BSDF and angle.
SAMPLES = 200_000
#: The family-wise level of a run's statistical checks.
ALPHA = 0.01
#: Values of a parameter a library names, where the command line gives none: a name of Mitsuba's, else 0.5.
DEFAULT_VALUES = {"alpha": 0.3, "reflectance": 0.8, "albedo": 0.8, "eta": 0.2, "k": 3.0, "ggx": 0.0,
                  "specular_reflectance": 1.0, "diffuse_reflectance": 0.5, "nonlinear": 0.0,
                  "sample_visible": 1.0, "int_ior": 1.5, "ext_ior": 1.0, "kd": 0.5, "ks": 0.5}
#: The value of a parameter neither given nor in DEFAULT_VALUES (the run says so).
FALLBACK_VALUE = 0.5
#: The BSDFs of our library the matrix runs by default: each model with its choices, at a low and a high
#: roughness.
OUR_DEFAULTS = ("diffuse", "conductor", "conductor:eta=0,k=1", "dielectric", "dielectric:int_ior=1.33", "plastic",
                "plastic:diffuse_reflectance=0.9,nonlinear=1", "microfacet:alpha=0.2,kd=0.3,ks=0.6",
                *(f"roughconductor:alpha={a},ggx={g},sample_visible={v}"
                  for a in (0.05, 0.5) for g in (0, 1) for v in (0, 1)),
                "roughdielectric:alpha=0.1,ggx=0,sample_visible=0", "roughdielectric:alpha=0.5,ggx=1",
                "roughplastic:alpha=0.1", "roughplastic:alpha=0.5,ggx=1,sample_visible=0,diffuse_reflectance=0.9,nonlinear=1")


#: Samples at normal incidence that tell whether a BSDF transmits.
PROBE_SAMPLES = 4096


def transmits(bsdf: BsdfFunctions) -> bool:
    """Whether the BSDF is an interface seen from both sides: a sample at normal incidence crosses it (a glass
    transmits 96 % there; a coated or opaque BSDF takes an index of refraction too, but nothing crosses)."""
    d = draw(bsdf, incident(0.0), PROBE_SAMPLES, 0)  # ChildFailed: its rows fail so
    return bool(np.any((d.wo[:, 2] < 0) & ~d.failed))


def row_angles(bsdf: BsdfFunctions, angles) -> list[float]:
    """The polar angles of wi of its rows: `angles` from above, and for a BSDF that transmits each also from below
    (180 - angle: wi mirrored under the surface)."""
    return [*angles, *(180.0 - a for a in angles)] if transmits(bsdf) else list(angles)


@dataclass(frozen=True)
class BsdfSpec:
    """A BSDF asked for: its name and the values given for some of its parameters."""

    name: str
    given: tuple[tuple[str, float], ...] = ()

    def values(self, parameters: list[str]) -> dict[str, float]:
        """Every parameter's value: given, else DEFAULT_VALUES, else FALLBACK_VALUE. ValueError for a given one it lacks."""
        given = dict(self.given)
        unknown = sorted(set(given) - set(parameters))
        if unknown:
            raise ValueError(f"{self.name} has no parameter {', '.join(unknown)} (it takes "
                             f"{', '.join(parameters) or 'none'})")
        return {p: given.get(p, DEFAULT_VALUES.get(p, FALLBACK_VALUE)) for p in parameters}


def parse_spec(text: str) -> BsdfSpec:
    """"roughconductor:alpha=0.1,ggx=1" (or a name alone); ValueError saying what was expected."""
    name, _, rest = text.partition(":")
    given = []
    for item in filter(None, rest.split(",")):
        key, eq, value = item.partition("=")
        try:
            number = float(value)
        except ValueError:
            number = None
        if eq and key.strip() and number is None:
            raise ValueError(f"--bsdf {text}: the value of {key.strip()} must be a number, not {value!r}")
        if not eq or not key.strip() or number is None:
            raise ValueError(f"--bsdf {text}: expected NAME or NAME:param=value,param=value (e.g. "
                             f"roughconductor:alpha=0.1,ggx=1), not {item!r}")
        given.append((key.strip(), number))
    if not name.strip().isidentifier():
        raise ValueError(f"--bsdf {text}: {name!r} is not a BSDF name (letters, digits and _)")
    return BsdfSpec(name.strip(), tuple(given))


@dataclass
class BsdfRow:
    """One BSDF at one incident angle: its checks, or the one line saying why it could not be checked."""

    label: str
    theta: float | None  # None: the BSDF could not be checked at any angle
    checks: dict[str, CheckResult] = field(default_factory=dict)
    failure: str | None = None
    seconds: float = 0.0
    #: The sampling check's cell counts ("observed", "expected", "reference"), for the page (not in results.json).
    histograms: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return self.failure is None and bool(self.checks) and all(c.passed for c in self.checks.values())

    def to_json(self) -> dict:
        return {"bsdf": self.label, "theta": self.theta, "pass": self.passed, "failure": self.failure,
                "seconds": round(self.seconds, 3), "checks": {k: c.to_json() for k, c in self.checks.items()}}


@dataclass(frozen=True)
class Entry:
    """A BSDF ready to check: its functions and the reference engine's (None: no such plugin there), or why it
    cannot be checked."""

    label: str
    bsdf: BsdfFunctions | None = None
    reference: BsdfFunctions | None = None
    failure: str | None = None
    extremes: tuple[BsdfFunctions, ...] = ()  # the same BSDF at the ends of its roughness range


def check_row(entry: Entry, theta: float | None, samples: int, seed: int, level: float,
              probe_failure: str | None = None) -> BsdfRow:
    """One row: `entry` at `theta` degrees (None: the entry could not be checked), its uniforms from `seed`."""
    if entry.failure is not None:
        return BsdfRow(entry.label, None, failure=entry.failure)
    row, start = BsdfRow(entry.label, theta), time.perf_counter()
    if probe_failure is not None:
        row.failure = probe_failure
        return row
    try:
        row.checks = check_bsdf_at(entry.bsdf, incident(theta), samples, seed, level, entry.reference,
                                   entry.extremes, row.histograms)
    except ChildFailed as e:  # the library (or Mitsuba) crashed, hung or wrote past its output
        row.failure = e.reason
    row.seconds = time.perf_counter() - start
    return row


def run_matrix(entries: list[Entry], angles=ANGLES, samples: int = SAMPLES, seed: int = 0, alpha: float = ALPHA,
               executor: Executor | None = None,
               on_status: Callable[[Status], None] | None = None) -> tuple[list[BsdfRow], float]:
    """Every entry at every angle (from below too where it transmits), a task per row on `executor` (serial by
    default; the rows' uniforms do not depend on it); returns the rows in order and the per-test level they were
    decided at."""
    rows_of, probe_failed = {}, {}
    for e in entries:
        if e.failure is None:
            try:
                rows_of[id(e)] = row_angles(e.bsdf, angles)
            except ChildFailed as err:  # crashed or hung on the probe: its rows fail so, without a call each
                rows_of[id(e)], probe_failed[id(e)] = list(angles), err.reason
    tests = sum(len(rows_of[id(e)]) * (len(OWN_STATISTICAL) + len(REFERENCE_STATISTICAL) * (e.reference is not None))
                for e in entries if e.failure is None)
    level = sidak_level(alpha, max(tests, 1))
    jobs = [(e, theta) for e in entries for theta in ([None] if e.failure is not None else rows_of[id(e)])]
    tasks = [Task(e.label if theta is None else f"{e.label} at {theta:g} degrees", check_row,
                  (e, theta, samples, seed * 7919 + i, level, probe_failed.get(id(e))))
             for i, (e, theta) in enumerate(jobs)]
    outcomes = (executor or SerialExecutor()).run(tasks, on_status)
    # A task without a value (a cluster's worker died under it) fails its row so.
    return [o.value if o.ok else BsdfRow(e.label, theta, failure=o.error) for o, (e, theta) in zip(outcomes, jobs)], level
