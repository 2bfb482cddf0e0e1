"""One image case's outcome: the tested engine's render against each reference, the comparisons and the
verdict, and its results.json entry."""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from harness.comparison.compare import Comparison
from harness.comparison.strategies import StrategyCheck
from harness.engines.base import RenderResult
from harness.images.case_verdict import CaseVerdict
from harness.images.oracle import Finding
from harness.images.references import Reference
from harness.images.suite import ImageCase
from harness.statistics.noise_fit import NoiseFit
from harness.statistics.constants import SIGNIFICANCE

@dataclass(kw_only=True)
class ImageResult:
    """One (scene, integrator): the tested engine's batches against each reference, and the case's verdict
    (`decision`, made by harness/images/evaluate.py; every verdict property here reads it).

    `tested` is None where the tested engine's render failed or was never made (the decision's `error` says
    why); `tested_engine` names that engine all the same.
    """

    case: ImageCase
    decision: CaseVerdict
    tested: RenderResult | None = None
    tested_engine: str = ""
    references: dict[str, Reference] = field(default_factory=dict)
    reference_source: str = "none"
    seed: int = 0
    alpha: float = SIGNIFICANCE
    run_seed: int = 0
    #: Against a reference image (--reference-image): how its noise fits its model.
    reference_fit: NoiseFit | None = None
    #: Where an exception no stage foresaw arose (the case failed with one line); written to the run's log.
    traceback: str = ""

    @property
    def verdict(self) -> str:
        """PASS, FAIL or INCONCLUSIVE (see harness/images/evaluate.py)."""
        return self.decision.verdict

    @property
    def passed(self) -> bool:
        return self.decision.passed

    @property
    def failed(self) -> bool:
        return self.decision.failed

    @property
    def comparisons(self) -> dict[str, Comparison]:
        return self.decision.comparisons

    @property
    def finding(self) -> Finding | None:
        return self.decision.finding

    @property
    def error(self) -> str | None:
        return self.decision.error

    @property
    def error_output(self) -> str:
        return self.decision.error_output

    @property
    def note(self) -> str | None:
        return self.decision.note

    @property
    def reference_problem(self) -> str | None:
        return self.decision.reference_problem

    @property
    def strategies(self) -> StrategyCheck | None:
        return self.decision.strategies

    def _strategies_json(self) -> dict:
        """The strategy check's block: its verdict, the strategy it names and its three comparisons, or why it
        did not run (nothing for an integrator without strategies)."""
        if self.strategies is not None:
            return {"strategies": self.strategies.to_json()}
        return {"strategies": {"skipped": self.decision.strategies_skipped}} if self.decision.strategies_skipped else {}

    @property
    def failures(self) -> str:
        return self.decision.failures

    @property
    def why(self) -> str:
        return self.decision.why

    @property
    def inconclusive(self) -> str:
        return self.decision.inconclusive

    def to_json(self) -> dict:
        if self.error is not None or self.tested is None:
            seconds = {k: r.seconds for k, r in self.references.items()}
            return {"integrator": self.case.integrator, "scene": self.case.scene, "engine": self.engine,
                    "pass": False, "verdict": "FAIL", "error": self.error, "tests": {}, "metrics": {},
                    "seconds": {**({self.engine: self.tested.seconds} if self.tested else {}), **seconds},
                    "reference": self.reference_source, "note": self.note, "seed": self.seed, "alpha": self.alpha,
                    "idiff": self.idiff, "error_output": self.error_output, **self._source()}
        first = self.comparisons[next(iter(self.comparisons))]  # the reference engine's (the closed form's after it)
        batch_means = self.tested.batch_means
        tested = self.engine
        return {
            "integrator": self.case.integrator, "scene": self.case.scene, "engine": tested, "pass": self.passed,
            "verdict": self.verdict, "inconclusive": self.inconclusive or None,
            "tests": {name: c.to_json() for name, c in self.comparisons.items()},
            "metrics": first.metrics,
            "seconds": {tested: self.tested.seconds, **{k: r.seconds for k, r in self.references.items()}},
            "reference": self.reference_source, "note": self.note, "error": None, "seed": self.seed,
            "alpha": self.alpha, "spp": {tested: self.tested.spp, **{k: r.spp for k, r in self.references.items()}},
            "batches": {tested: self.tested.count, **{k: r.summary.image.k for k, r in self.references.items()}},
            "image_mean": batch_means.mean(axis=0).tolist(),
            "image_mean_se": (batch_means.std(axis=0, ddof=1) / np.sqrt(len(batch_means))).tolist(),
            "idiff": self.idiff, "finding": self.finding.to_json() if self.finding else None, **self._source(),
            **self._reference_fit(), **self._strategies_json(),
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
        return self.tested.engine if self.tested is not None else self.tested_engine

    @cached_property
    def idiff(self) -> dict:
        """What idiff, at OpenImageIO's test-suite thresholds, says of the tested mean image against the
        reference's mean (the reference engine's, else the closed form's); verdict "n/a" with a reason when
        there is no pair of images to compare."""
        ref = next(iter(self.references.values()), None)
        if self.error is not None or self.tested is None or ref is None:
            return {"verdict": "n/a", "reason": self.error or "no reference image"}
        from harness.comparison.idiff import idiff
        try:
            return idiff(self.tested.mean, ref.summary.mean_image)
        except Exception as e:  # a side report never breaks the run
            return {"verdict": "n/a", "reason": f"idiff failed: {e}"}
