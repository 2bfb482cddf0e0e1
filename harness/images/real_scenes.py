"""The real scenes (scenes/real/, Mitsuba's own files) as their own section of an image run: their verdicts,
and the cases their integrators' entries declare not applicable (listed with why, never run, not failures)."""
from __future__ import annotations

from harness.images.result import ImageResult
from harness.images.suite import ImageCase


def split(results: list[ImageResult]) -> tuple[list[ImageResult], list[ImageResult]]:
    """Our own scenes' results, then the real scenes'."""
    return [r for r in results if r.case.group != "real"], [r for r in results if r.case.group == "real"]


def real_scenes_json(results: list[ImageResult], not_applicable: list[tuple[ImageCase, str]]) -> dict:
    """results.json's `real_scenes` group: each case's verdict (its full entry is in `images`) and the
    not-applicable cases with their reasons."""
    real = [r for r in results if r.case.group == "real"]
    skipped = [(c, why) for c, why in not_applicable if c.group == "real"]
    return {"pass": not any(r.failed for r in real) and any(r.passed for r in real),
            "scenes": sorted({r.case.scene for r in real} | {c.scene for c, _ in skipped}),
            "cases": [{"scene": r.case.scene, "integrator": r.case.integrator, "pass": r.passed, "verdict": r.verdict,
                       "reference": r.reference_source} for r in real],
            "not_applicable": [{"scene": c.scene, "integrator": c.integrator, "reason": why} for c, why in skipped]}
