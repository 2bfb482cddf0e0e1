"""evaluate() with a case's strategies (harness/images/evaluate.py): three renders of one image that agree leave
the verdict to the comparisons with the references; a strategy that differs fails the case, even where those
comparisons pass, and is named in why it failed; a strategy whose render failed fails the case with its reason."""
from __future__ import annotations

import numpy as np

from harness.comparison.summary import summarize
from harness.engines.base import RenderResult
from harness.images.evaluate import RenderFailure, evaluate
from harness.images.references import Reference
from harness.images.suite import ImageCase
from tools.strategy_triples import DOUBLE_COUNT, null_triple, planted

CASE = ImageCase("plane_rect_light", "direct")
SPP = 32


def _render(batches: np.ndarray, seed: int = 1) -> RenderResult:
    return RenderResult("mcval", "plane_rect_light", "direct", SPP, seed, batches.astype(np.float32), {"total": 1.0})


def _judge(triple: dict[str, np.ndarray], **strategies):
    """The case with the triple's "mis" as the tested render, another null "mis" as the reference."""
    reference = null_triple(np.random.default_rng(99), spp=SPP)["mis"]
    renders = {name: _render(b, seed) for seed, (name, b) in enumerate(triple.items())}
    renders.update(strategies)
    return evaluate(CASE, renders["mis"], {"mitsuba": Reference(summarize(reference), SPP, {}, "stored")},
                    alpha=0.01, reference="mitsuba", strategies=renders)


def test_agreeing_strategies_leave_the_verdict_to_the_references():
    judged = _judge(null_triple(np.random.default_rng(1), spp=SPP))
    assert judged.verdict == "PASS" and judged.strategies.verdict == "AGREE" and judged.why == ""


def test_a_strategy_that_differs_fails_a_case_its_references_pass():
    triple = planted(null_triple(np.random.default_rng(2), spp=SPP), "mats", 0.3)
    judged = _judge(triple)
    assert judged.comparisons["mitsuba"].passed  # the tested render (mis) is right
    assert judged.verdict == "FAIL" and judged.strategies.odd == "mats"
    assert judged.why.startswith("strategies DIFFERS: mats differs from ems and mis")
    assert judged.note is None  # no comparison with a reference failed: no factor to name


def test_the_wrong_twin_of_the_check_mis_double_counting_is_named():
    judged = _judge(planted(null_triple(np.random.default_rng(3), spp=SPP), "mis", 0.2, DOUBLE_COUNT))
    assert judged.failed and judged.strategies.odd == "mis"


def test_a_failed_strategy_render_fails_the_case_with_its_reason():
    judged = _judge(null_triple(np.random.default_rng(4), spp=SPP),
                    ems=RenderFailure(reason="mcval render of the ems strategy: exited with status 1"))
    assert judged.failed and judged.error == "mcval render of the ems strategy: exited with status 1"
    assert judged.strategies is None


def test_without_strategies_the_case_says_why():
    reference = null_triple(np.random.default_rng(5), spp=SPP)["mis"]
    tested = _render(null_triple(np.random.default_rng(6), spp=SPP)["mis"])
    judged = evaluate(CASE, tested, {"mitsuba": Reference(summarize(reference), SPP, {}, "stored")}, alpha=0.01,
                      reference="mitsuba", strategies_skipped="point lights, which BSDF sampling never finds")
    assert judged.strategies is None and judged.strategies_skipped.startswith("point lights")
