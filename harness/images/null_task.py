"""One null image comparison as a task: two independent renders of the same case by engines that agree
(the tested engine twice, the reference engine twice, the tested engine and the closed form), compared at every
calibration level; for the tested engine
twice, also whether a planted bias (the whole image, or one 8x8 tile) is found at the default level."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.distributed.bundle import Bundle
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine
from harness.images.case_task import on_files
from harness.comparison.compare import SCALES, compare_summaries
from harness.comparison.summary import summarize
from harness.images.references import REFERENCE_BATCHES
from harness.images.suite import ImageCase
from harness.statistics.calibration_rates import CALIBRATION_LEVELS
from harness.statistics.constants import IMAGE_BATCHES, TILE_SIZE
from harness.integrators import entry

#: The pairs of engines whose renders of one case must agree.
KINDS = ("test-test", "reference-reference", "test-closed-form")
#: Relative biases planted for the power curves.
BIASES = tuple(float(b) for b in np.geomspace(1e-4, 1.0, 17))


@dataclass
class NullJob:
    kind: str
    case: ImageCase
    seed: int
    resolution: int
    alpha: float            # the validation's per-comparison level, for the power figures
    test: Engine            # the engine under test
    reference: Engine


def _render(engine: Engine, case: ImageCase, spp: int, batches: int, seed: int, res: int) -> np.ndarray:
    return engine.render(str(engine.scene_file(case.path)), case.integrator, spp, batches, seed, {"res": str(res)}).batches


def null_comparison(job: NullJob, bundle: Bundle | None = None) -> dict:
    """The rejections of one null comparison by scale and level, its image-scale smallest p-value, and
    (the tested engine twice) which planted biases the default level finds."""
    case = on_files(job.case, bundle)
    spp, signed = case.test_spp, entry(case.integrator).signed
    # The test side as the validation renders the tested engine's; the reference side with more batches, as a
    # reference has.
    test_engine, ref_engine = {"test-test": (job.test, job.test),
                               "reference-reference": (job.reference, job.reference),
                               "test-closed-form": (job.test, AnalyticEngine())}[job.kind]
    test = _render(test_engine, case, spp, IMAGE_BATCHES, job.seed, job.resolution)
    if job.kind == "test-closed-form":
        ref_spp, ref_batches = AnalyticEngine.samples_for(case.integrator, spp), IMAGE_BATCHES
    else:
        ref_spp, ref_batches = spp, REFERENCE_BATCHES
    reference = summarize(_render(ref_engine, case, ref_spp, ref_batches, job.seed + 1, job.resolution))
    samples = (spp, ref_spp)
    rejected, summary = {}, summarize(test)
    # One engine twice draws one estimator, so the noise is judged too; against the closed form only where it
    # draws the integrator's estimator, as the suite judges it (harness/images/evaluate.py).
    same = job.kind != "test-closed-form" or AnalyticEngine.draws_estimator(case.integrator)
    for level in CALIBRATION_LEVELS:
        c = compare_summaries(summary, reference, level, signed, samples=samples, metrics=False, power=False,
                              same_estimator=same)
        rejected[str(level)] = {**{s.scale: not s.passed for s in c.scales},
                                # Against another estimator the variance ratio is reported, not judged.
                                "variance": c.variance is not None and c.variance.same_estimator
                                and c.variance.result is not None and c.variance.result.rejects,
                                "firefly": c.variance is not None and c.variance.excess is not None
                                and c.variance.excess.rejects,
                                "outlier": not c.no_outlier, "whole": not c.passed}
    out = {"kind": job.kind, "case": case.key, "integrator": case.integrator, "rejected": rejected,
           "image_min_p": c.scales[SCALES.index("image")].min_p}
    if job.kind == "test-test":
        out["global"], out["tile"] = _planted(test, reference, job, signed, samples)
    return out


def _planted(test: np.ndarray, reference, job: NullJob, signed: bool, samples) -> tuple[list[bool], list[bool]]:
    """Per bias of BIASES: found by the image scale when every pixel is scaled by 1 + b; found by the tile
    scale when one tile (drawn by the job's seed among those with a non-zero mean) is."""
    h, w = test.shape[1:3]
    tiles = [(y, x) for y in range(0, h - TILE_SIZE + 1, TILE_SIZE) for x in range(0, w - TILE_SIZE + 1, TILE_SIZE)
             if np.abs(test[:, y:y + TILE_SIZE, x:x + TILE_SIZE].mean()) > 0]
    y, x = tiles[np.random.default_rng(job.seed).integers(len(tiles))] if tiles else (0, 0)
    found_global, found_tile = [], []
    for b in BIASES:
        c = compare_summaries(summarize(test * (1 + b)), reference, job.alpha, signed, samples=samples, metrics=False,
                              power=False, same_estimator=True)
        found_global.append(not c.scales[SCALES.index("image")].passed)
        planted = test.copy()
        planted[:, y:y + TILE_SIZE, x:x + TILE_SIZE] *= 1 + b
        c = compare_summaries(summarize(planted), reference, job.alpha, signed, samples=samples, metrics=False,
                              power=False, same_estimator=True)
        found_tile.append(not c.scales[SCALES.index("tile")].passed)
    return found_global, found_tile
