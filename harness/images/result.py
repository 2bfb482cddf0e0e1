"""One image case's outcome: the tested engine's render against each reference, the comparisons and the
verdict, and its results.json entry."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from harness.comparison.compare import Comparison
from harness.engines.base import RenderResult
from harness.foreign_text import foreign
from harness.images.oracle import Finding
from harness.images.references import Reference
from harness.images.suite import ImageCase
from harness.statistics.noise_fit import NoiseFit
from harness.statistics.constants import SIGNIFICANCE

#: On the other cases of a scene whose normals failed: normals see only the camera and the geometry, unless
#: the fault is one that every image shares (a scale applied to every output).
GEOMETRY_NOTE = ("normals failed on this scene: a camera or geometry mismatch, or a fault every image shares "
                 "(its other failures may have that cause)")


@dataclass
class ImageResult:
    """One (scene, integrator): our batches against each reference, and the verdicts.

    `error` (one line) says why a render failed (crashed, killed, timed out, reported an error); the case
    then fails without comparisons, and `ours` is None if our render was the one that failed. `finding` is
    set when the closed form overrules a reference (harness/images/oracle.py): that reference's failed
    comparison then does not fail the case.
    """

    case: ImageCase
    ours: RenderResult | None
    references: dict[str, Reference]
    comparisons: dict[str, Comparison]
    reference_source: str
    seed: int
    note: str | None = None
    alpha: float = SIGNIFICANCE
    run_seed: int = 0
    error: str | None = None
    finding: Finding | None = None
    tested: str = ""  # the tested engine's name, for a result without our render
    #: The last lines (up to 50) a failed render printed, where it printed any.
    error_output: str = ""
    #: Against a reference image (--reference-image): how its noise fits its model, and why it cannot be
    #: compared under that model (one line; the case then fails whatever the comparison says).
    reference_fit: NoiseFit | None = None
    reference_problem: str | None = None
    #: For an INCONCLUSIVE case: the samples per pixel that would decide it, or why none would (one line).
    decisive_budget: str = ""
    #: Where an exception no stage foresaw arose (the case failed with one line); written to the run's log.
    traceback: str = ""

    def __post_init__(self) -> None:
        # Why a render failed is often an engine's own text (Mitsuba's message quoting a scene's 1 MB tag
        # name, a renderer's output): bounded here, whichever engine and stage it came from.
        if self.error is not None:
            self.error = foreign(self.error)
        self.error_output = foreign(self.error_output, keep="tail")

    @property
    def _deciding(self) -> list[Comparison]:
        overruled = self.finding.overruled if self.finding else None
        return [c for name, c in self.comparisons.items() if name != overruled]

    @property
    def verdict(self) -> str:
        """"FAIL" when a render or a deciding comparison failed; "PASS" when none failed and one could have
        shown a defect; else "INCONCLUSIVE" (no signal, or a detectable bias above INCONCLUSIVE_BIAS)."""
        deciding = self._deciding
        if self.error is not None or self.reference_problem is not None or not deciding \
                or any(not c.passed for c in deciding):
            return "FAIL"
        return "PASS" if any(c.verdict == "PASS" for c in deciding) else "INCONCLUSIVE"

    @property
    def passed(self) -> bool:
        return self.verdict == "PASS"

    @property
    def failed(self) -> bool:
        return self.verdict == "FAIL"

    @property
    def failures(self) -> str:
        """Each failed comparison's reason, one line ("against mitsuba: ...; against analytic: ...")."""
        return "; ".join(f"against {n}: {c.reason}" for n, c in self.comparisons.items() if not c.passed)

    @property
    def why(self) -> str:
        """Why the case failed, cause first: the render's error, the named cause (a factor, |n|), the reference
        image's misfit, then the failed comparisons; "" when it did not fail."""
        if not self.failed:
            return ""
        return "; ".join(x for x in (self.error, self.note, self.reference_problem,
                                     None if self.error else self.failures) if x)

    @property
    def inconclusive(self) -> str:
        """Why the case is INCONCLUSIVE, with what would decide it ("" when it is not)."""
        if self.verdict != "INCONCLUSIVE":
            return ""
        why = next(c.inconclusive for c in self._deciding if c.inconclusive)
        return why + (f"; {self.decisive_budget}" if self.decisive_budget else "")

    def to_json(self) -> dict:
        if self.error is not None or self.ours is None:
            seconds = {k: r.seconds for k, r in self.references.items()}
            return {"integrator": self.case.integrator, "scene": self.case.scene, "engine": self.engine,
                    "pass": False, "verdict": "FAIL", "error": self.error, "tests": {}, "metrics": {},
                    "seconds": {**({self.engine: self.ours.seconds} if self.ours else {}), **seconds},
                    "reference": self.reference_source, "note": self.note, "seed": self.seed, "alpha": self.alpha,
                    "idiff": self.idiff, "error_output": self.error_output, **self._source()}
        first = self.comparisons[next(iter(self.comparisons))]  # the reference engine's (the closed form's after it)
        batch_means = self.ours.batch_means
        tested = self.engine
        return {
            "integrator": self.case.integrator, "scene": self.case.scene, "engine": tested, "pass": self.passed,
            "verdict": self.verdict, "inconclusive": self.inconclusive or None,
            "tests": {name: c.to_json() for name, c in self.comparisons.items()},
            "metrics": first.metrics,
            "seconds": {tested: self.ours.seconds, **{k: r.seconds for k, r in self.references.items()}},
            "reference": self.reference_source, "note": self.note, "error": None, "seed": self.seed,
            "alpha": self.alpha, "spp": {tested: self.ours.spp, **{k: r.spp for k, r in self.references.items()}},
            "batches": {tested: self.ours.count, **{k: r.summary.image.k for k, r in self.references.items()}},
            "image_mean": batch_means.mean(axis=0).tolist(),
            "image_mean_se": (batch_means.std(axis=0, ddof=1) / np.sqrt(len(batch_means))).tolist(),
            "idiff": self.idiff, "finding": self.finding.to_json() if self.finding else None, **self._source(),
            **self._reference_fit(),
        }

    def _reference_fit(self) -> dict:
        if self.reference_fit is None:
            return {}
        return {"reference_fit": self.reference_fit.to_json(), "reference_problem": self.reference_problem}

    def _source(self) -> dict:
        """A user's scene file (--scene) as given, and what its preparation left out."""
        if not self.case.source:
            return {}
        return {"scene_file": self.case.source, **({"scene_notes": list(self.case.notes)} if self.case.notes else {})}

    @property
    def engine(self) -> str:
        """The tested engine's name (the key of its figures in results.json)."""
        return self.ours.engine if self.ours is not None else self.tested

    @cached_property
    def idiff(self) -> dict:
        """What idiff, at OpenImageIO's test-suite thresholds, says of our mean image against the
        reference's mean (the reference engine's, else the closed form's); verdict "n/a" with a reason when
        there is no pair of images to compare."""
        ref = next(iter(self.references.values()), None)
        if self.error is not None or self.ours is None or ref is None:
            return {"verdict": "n/a", "reason": self.error or "no reference image"}
        from harness.comparison.idiff import idiff
        try:
            return idiff(self.ours.mean, ref.summary.mean_image)
        except Exception as e:  # a side report never breaks the run
            return {"verdict": "n/a", "reason": f"idiff failed: {e}"}
