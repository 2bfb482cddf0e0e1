"""How often the image comparison rejects when nothing is wrong, measured, and the smallest biases it finds.

Null comparisons of three kinds (KINDS: the tested engine against itself at independent seeds, the reference
engine against itself, the tested engine against the closed form), cycled over CASES, each compared at every
calibration level: the observed false-alarm rate per kind, per scale (pixel, tile, image) and for the whole comparison, with exact
(Clopper-Pearson) intervals simultaneous over every interval of the calibration, beside the nominal level.
Power: per integrator, the smallest relative bias of the whole image and of one 8x8 tile that the
validation's per-comparison level finds in 90 % of test-test comparisons."""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.base import Engine
from harness.comparison.compare import SCALES
from harness.images.null_task import BIASES, KINDS, NullJob, null_comparison
from harness.images.references import RESOLUTION
from harness.images.run import closed_forms, comparison_level, strategy_checks
from harness.images.suite import ImageCase, select_cases
from harness.statistics.calibration_rates import CALIBRATION_CONFIDENCE, CALIBRATION_LEVELS, Rate, clopper_pearson
from harness.statistics.constants import OUTLIER_LEVEL, sidak_level

#: The cases each kind cycles over (test-closed-form: those with a closed form). None is noiseless on both
#: sides (normals, or ao, on a lone plane: both engines exact, nothing could reject, which would only
#: dilute the rate); cornell:normals is noisy along its edges and gives the normals' power.
CASES = {
    "test-test": ("cornell:normals", "cornell:simple", "cornell:ao", "sphere_floor_unit:simple", "crevice:ao",
                  "plane_point:simple", "grazing_light:simple", "close_light:simple", "cornell:direct",
                  "close_light:direct"),
    "reference-reference": ("plane_point:simple", "cornell:ao", "sphere_floor_unit:simple", "cornell:direct"),
    "test-closed-form": ("plane_point:simple", "sphere_floor_unit:simple", "sphere_floor_unit:ao",
                         "plane_rect_light:direct"),
}
#: Heavy-tailed estimators among CASES: a point light at grazing angles, one close to a surface (1/r^2 within a
#: pixel's footprint).
HEAVY_TAILED = ("grazing_light:simple", "close_light:simple", "close_light:direct")
#: The parts of a comparison whose rejections are counted: the scales, the image-wide variance test, the
#: per-pixel and per-tile excess of noise (fireflies), a batch standing apart, and the whole comparison.
PARTS = (*SCALES, "variance", "firefly", "outlier", "whole")
#: Detected in this fraction of comparisons: the power figures' bias.
POWER = 0.9


def validation_alpha(tested: Engine) -> float:
    """The per-comparison level of a default `validate` of `tested`."""
    cases = select_cases(None)
    return comparison_level(cases, closed_forms(cases), strategy_checks(cases, tested))


def _nominal(part: str, level: float) -> float:
    """The level a part of a comparison runs at, for a comparison at `level`: a scale and the noise check take
    their Sidak share of it, and the noise check's two tests (image-wide, per element) half of that each; a
    batch standing apart is judged at the fixed OUTLIER_LEVEL."""
    if part == "whole":
        return level
    if part == "outlier":
        return OUTLIER_LEVEL
    share = sidak_level(level, len(SCALES) + 1)
    return sidak_level(share, 2) if part in ("variance", "firefly") else share


def _case(key: str) -> ImageCase:
    scene, integrator = key.split(":")
    return ImageCase(scene, integrator)


@dataclass
class ImageCalibration:
    results: list[dict]      # one per null comparison (null_task.null_comparison)
    alpha: float             # the validation's per-comparison level (power)
    seconds: float
    failed: list[str]        # tasks that gave no result, and why

    def blocks(self) -> list[dict]:
        """Per kind and for all kinds together, per scale and for the whole comparison: the rates."""
        groups = [(kind, [r for r in self.results if r["kind"] == kind]) for kind in KINDS]
        groups.append(("all", self.results))
        heavy = [r for r in self.results if r["case"] in HEAVY_TAILED]
        if heavy:
            groups.append(("heavy-tailed", heavy))
        intervals = len(groups) * len(PARTS) * len(CALIBRATION_LEVELS)
        each = 1.0 - (1.0 - CALIBRATION_CONFIDENCE) / intervals
        out = []
        for kind, rs in groups:
            for part in PARTS:
                for level in CALIBRATION_LEVELS:
                    nominal = _nominal(part, level)
                    k = sum(r["rejected"][str(level)].get(part, False) for r in rs)
                    rate = Rate(nominal, len(rs), k, *clopper_pearson(k, len(rs), each))
                    out.append({"kind": kind, "scale": part, "comparison_level": level, **rate.to_json()})
        return out

    def power(self) -> dict:
        """Per integrator: the detection fraction at each planted bias, and the smallest found POWER of the time."""
        out = {}
        for integrator in sorted({r["integrator"] for r in self.results if r["kind"] == "test-test"}):
            rs = [r for r in self.results if r["kind"] == "test-test" and r["integrator"] == integrator]
            entry = {"comparisons": len(rs), "biases": list(BIASES)}
            for what in ("global", "tile"):
                found = np.mean([r[what] for r in rs], axis=0)
                entry[f"{what}_found"] = found.tolist()
                hits = [b for b, f in zip(BIASES, found) if f >= POWER]
                entry[f"{what}_bias_{int(POWER * 100)}"] = hits[0] if hits else None
            out[integrator] = entry
        return out

    @property
    def within(self) -> bool:
        """Every whole-comparison rate lies within its interval of the nominal level, and nothing failed."""
        return self._within(self.blocks())

    @property
    def sound(self) -> bool:
        """Nothing failed and no rate (of a scale or the whole comparison) lies above its nominal level
        beyond its interval. A conservative rate costs power, which the power figures show, never a false FAIL."""
        return self._sound(self.blocks())

    def _within(self, blocks: list[dict]) -> bool:
        return not self.failed and all(b["within"] for b in blocks if b["scale"] == "whole")

    def _sound(self, blocks: list[dict]) -> bool:
        return not self.failed and not any(b["verdict"] == "liberal" for b in blocks)

    def to_json(self) -> dict:
        blocks = self.blocks()
        whole = [b for b in blocks if b["kind"] == "all" and b["scale"] == "whole"]
        return {"comparisons": len(self.results), "false_alarm_rate": whole[-1]["false_alarm_rate"],
                "level": whole[-1]["level"], "pass": self._sound(blocks), "within": self._within(blocks),
                "blocks": blocks, "power": self.power(), "power_level": self.alpha,
                "image_min_p": [r["image_min_p"] for r in self.results], "failed": self.failed,
                "seconds": self.seconds}


def calibrate_images(test: Engine, reference: Engine, per_kind: int, seed: int = 0,
                     executor: Executor | None = None, on_status: Callable[[Status], None] | None = None,
                     resolution: int = RESOLUTION) -> ImageCalibration:
    """`per_kind` null comparisons of each kind, each with its own seeds."""
    from harness.images.case_task import share_scene_bundles

    executor = executor or SerialExecutor()
    alpha = validation_alpha(test)
    jobs = [NullJob(kind, _case(CASES[kind][i % len(CASES[kind])]), 1_000_003 * seed + 2 * (i + per_kind * k),
                    resolution, alpha, test, reference)
            for k, kind in enumerate(KINDS) for i in range(per_kind)]
    bundles = share_scene_bundles(executor, [j.case for j in jobs], (test, reference))
    start = time.perf_counter()
    outcomes = executor.run([Task(f"{j.kind} {j.case.key}", null_comparison, (j, bundles.get(j.case.scene)))
                             for j in jobs], on_status)
    failed = [f"{j.kind} {j.case.key} seed {j.seed}: {o.error}" for j, o in zip(jobs, outcomes) if not o.ok]
    return ImageCalibration([o.value for o in outcomes if o.ok], alpha, time.perf_counter() - start, failed)
