"""Running the image suite: our renders against Mitsuba (and closed forms), with layered verdicts."""
from __future__ import annotations

import zlib
from dataclasses import dataclass
from typing import Callable

import numpy as np

from harness.compare import Comparison, compare_summaries, summarize
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine, RenderResult
from harness.image_suite import OUR_SPP, ImageCase
from harness.references import RESOLUTION, Reference, load_reference, render_reference
from harness.stats import IMAGE_BATCHES, SIGNIFICANCE, sidak_level

GEOMETRY_NOTE = "camera or geometry mismatch (normals failed on this scene)"


@dataclass
class ImageResult:
    """One (scene, integrator): our batches against each reference, and the verdicts."""

    case: ImageCase
    ours: RenderResult
    references: dict[str, Reference]
    comparisons: dict[str, Comparison]
    reference_source: str
    seed: int
    note: str | None = None
    alpha: float = SIGNIFICANCE
    run_seed: int = 0

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.comparisons.values())

    def to_json(self) -> dict:
        mitsuba = self.comparisons.get("mitsuba")
        batch_means = self.ours.batches.mean(axis=(1, 2))
        return {
            "integrator": self.case.integrator, "scene": self.case.scene, "pass": self.passed,
            "tests": {name: c.to_json() for name, c in self.comparisons.items()},
            "metrics": mitsuba.metrics if mitsuba else next(iter(self.comparisons.values())).metrics,
            "seconds": {"mcval": self.ours.seconds, **{k: r.seconds for k, r in self.references.items()}},
            "reference": self.reference_source, "note": self.note, "seed": self.seed, "alpha": self.alpha,
            "spp": {"mcval": self.ours.spp, **{k: r.spp for k, r in self.references.items()}},
            "batches": {"mcval": len(self.ours.batches), **{k: r.summary.image.k for k, r in self.references.items()}},
            "image_mean": batch_means.mean(axis=0).tolist(),
            "image_mean_se": (batch_means.std(axis=0, ddof=1) / np.sqrt(len(batch_means))).tolist(),
        }


def case_seed(case: ImageCase, seed: int) -> int:
    """Distinct seeds per case, so two integrators on one scene do not share their noise."""
    return (zlib.crc32(case.key.encode()) + 7919 * seed) % 2**31


def run_images(cases: list[ImageCase], ours: Engine, mitsuba: Engine, seed: int = 0,
               on_progress: Callable[[ImageCase], None] | None = None,
               on_message: Callable[[str], None] | None = None) -> tuple[list[ImageResult], float]:
    """Every case; all comparisons of the run share a family-wise false-alarm rate of SIGNIFICANCE
    (Sidak). Returns the results and the per-comparison alpha."""
    analytic = AnalyticEngine()
    params = {"res": str(RESOLUTION)}
    has_closed_form = {c: analytic.supports(str(c.path), params) for c in cases}
    alpha = sidak_level(SIGNIFICANCE, len(cases) + sum(has_closed_form.values()))
    geometry_failed: set[str] = set()
    results = []
    for case in cases:
        reference, source = load_reference(case, mitsuba)
        if reference is None:
            if on_message:
                on_message(f"{case.key}: {source}; rendering it now (`make references` stores it)")
            reference = render_reference(case, mitsuba)
            source = f"rendered now ({source})"
        s = case_seed(case, seed)
        mine = ours.render(str(case.path), case.integrator, OUR_SPP[case.integrator], IMAGE_BATCHES, s, params)
        summary = summarize(mine.batches)
        signed = case.integrator == "normals"
        references = {"mitsuba": reference}
        if has_closed_form[case]:
            exact = analytic.render(str(case.path), case.integrator, OUR_SPP[case.integrator], IMAGE_BATCHES,
                                    s + 1, params)
            references["analytic"] = Reference(summarize(exact.batches), exact.spp, exact.seconds, "closed form")
        comparisons = {name: compare_summaries(summary, ref.summary, alpha, signed=signed)
                       for name, ref in references.items()}
        note = GEOMETRY_NOTE if case.scene in geometry_failed else None
        result = ImageResult(case, mine, references, comparisons, source, s, note, alpha, seed)
        if case.integrator == "normals" and not result.passed:
            geometry_failed.add(case.scene)
            result.note = GEOMETRY_NOTE
        results.append(result)
        if on_progress:
            on_progress(case)
    return results, alpha
