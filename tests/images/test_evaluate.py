"""evaluate() decides a case from its renders given as data (harness/images/evaluate.py): synthetic batches of
an estimator that averages spp samples of 0 or 1 per pixel, a planted wrong twin beside each right one."""
from __future__ import annotations

import builtins
from pathlib import Path

import numpy as np
import pytest

from harness.comparison.summary import summarize
from harness.engines.base import RenderResult
from harness.images.evaluate import (GEOMETRY_NOTE, RenderFailure, evaluate, failure, with_scene_notes)
from harness.images.references import CLOSED_FORM, Reference
from harness.images.suite import ImageCase

CASE = ImageCase("plane_ao", "ao")
SPP, K, SIZE = 64, 8, 32
ALPHA = 0.01


def _batches(seed: int, scale: float = 1.0, spp: int = SPP, lit: float = 0.6) -> np.ndarray:
    """K batches of a grey image: each pixel the mean of `spp` samples that are 1 with probability `lit`."""
    rng = np.random.default_rng(seed)
    hits = rng.binomial(spp, lit, size=(K, SIZE, SIZE, 1)) / spp
    return (np.repeat(hits, 3, axis=-1) * scale).astype(np.float32)


def _tested(batches: np.ndarray) -> RenderResult:
    return RenderResult("mcval", "plane_ao", "ao", SPP, 1, batches, {"total": 1.0})


def _reference(batches: np.ndarray, source: str = "stored reference") -> Reference:
    return Reference(summarize(batches), SPP, {"total": 2.0}, source)


def _evaluate(tested, references, **kw):
    return evaluate(CASE, tested, references, alpha=ALPHA, reference="mitsuba", **kw)


def test_a_passing_pair_passes_and_a_biased_tested_image_fails():
    right = _evaluate(_tested(_batches(1)), {"mitsuba": _reference(_batches(2))})
    assert right.verdict == "PASS" and right.passed and right.why == "" and right.finding is None
    assert list(right.comparisons) == ["mitsuba"] and right.comparisons["mitsuba"].passed
    biased = _evaluate(_tested(_batches(1, scale=1.05)), {"mitsuba": _reference(_batches(2))})
    assert biased.verdict == "FAIL" and "image" in biased.comparisons["mitsuba"].failed_scales
    assert biased.why.startswith(biased.note or "against mitsuba") and "against mitsuba" in biased.why


def test_a_nan_pixel_fails_through_the_finite_check():
    batches = _batches(1)
    batches[3, 5, 7, 1] = np.nan
    judged = _evaluate(_tested(batches), {"mitsuba": _reference(_batches(2))})
    assert judged.failed and not judged.comparisons["mitsuba"].finite.passed
    assert "finite" in judged.comparisons["mitsuba"].failed_checks


def test_two_black_images_do_not_pass():
    black = np.zeros((K, SIZE, SIZE, 3), np.float32)
    judged = _evaluate(_tested(black), {"mitsuba": _reference(black)})
    assert judged.verdict == "INCONCLUSIVE" and not judged.passed and not judged.failed
    assert judged.inconclusive.startswith("no signal")
    # Its twin: one side black where the other is lit fails outright.
    assert _evaluate(_tested(black), {"mitsuba": _reference(_batches(2))}).failed


def test_the_closed_form_overrules_a_reference_that_breaks_it():
    exact = _reference(_batches(3), CLOSED_FORM)
    judged = _evaluate(_tested(_batches(1)), {"mitsuba": _reference(_batches(2, scale=1.05)), "analytic": exact})
    assert not judged.comparisons["mitsuba"].passed and judged.comparisons["analytic"].passed
    assert judged.passed and judged.finding is not None and judged.finding.overruled == "mitsuba"
    assert list(judged.deciding) == ["analytic"]
    assert judged.finding.text.startswith("reference breaks the closed form")
    assert all(r == pytest.approx(1.05, abs=0.01) for r in judged.finding.mean_ratio["mitsuba"])
    assert all(r == pytest.approx(1.0, abs=0.01) for r in judged.finding.mean_ratio["tested"])


def test_a_tested_image_that_breaks_the_closed_form_is_not_overruled():
    exact = _reference(_batches(3), CLOSED_FORM)
    judged = _evaluate(_tested(_batches(1, scale=1.05)), {"mitsuba": _reference(_batches(2)), "analytic": exact})
    assert judged.failed and judged.finding is None
    assert not judged.comparisons["analytic"].passed and not judged.comparisons["mitsuba"].passed


def test_a_closed_form_of_the_mean_only_judges_the_mean_not_the_noise(monkeypatch):
    import dataclasses

    import harness.engines.analytic as analytic_module
    import harness.images.evaluate as evaluate_module
    from harness.integrators import entry

    # The exact mean, without the estimator's noise: a noisy tested render of the right mean must pass it...
    mean = np.full((K, SIZE, SIZE, 3), 0.6, np.float32)
    exact = _reference(mean + np.random.default_rng(4).normal(0, 1e-4, mean.shape).astype(np.float32), CLOSED_FORM)
    ao = entry("ao")
    mean_only = dataclasses.replace(ao, analytic=dataclasses.replace(ao.analytic, draws_estimator=False))
    for module in (evaluate_module, analytic_module):  # the case's entry, and the closed form's (draws_estimator)
        monkeypatch.setattr(module, "entry", lambda name: mean_only)
    right = _evaluate(_tested(_batches(1)), {"mitsuba": _reference(_batches(2)), "analytic": exact})
    assert right.passed and right.comparisons["analytic"].passed
    # ... and a biased one fails it; where the closed form claims to draw the estimator, the noise fails it.
    biased = _evaluate(_tested(_batches(1, scale=1.05)), {"mitsuba": _reference(_batches(2)), "analytic": exact})
    assert biased.failed and not biased.comparisons["analytic"].passed
    for module in (evaluate_module, analytic_module):
        monkeypatch.setattr(module, "entry", lambda name: ao)
    claimed = _evaluate(_tested(_batches(1)), {"mitsuba": _reference(_batches(2)), "analytic": exact})
    assert not claimed.comparisons["analytic"].passed and "variance" in claimed.comparisons["analytic"].failed_checks


def test_the_first_failure_is_the_cases_and_a_missing_render_is_an_error():
    ref_failed = RenderFailure(reason="Mitsuba reference: crashed", output="last words")
    judged = _evaluate(RenderFailure(reason="mcval render: crashed"), {"mitsuba": ref_failed})
    assert judged.failed and judged.error == "Mitsuba reference: crashed" and judged.error_output == "last words"
    assert not judged.comparisons
    closed = _evaluate(_tested(_batches(1)), {"mitsuba": _reference(_batches(2)),
                                               "analytic": RenderFailure(reason="closed form: no")})
    assert closed.error == "closed form: no"
    with pytest.raises(ValueError, match="no tested render"):
        _evaluate(None, {"mitsuba": _reference(_batches(2))})
    problem = evaluate(ImageCase("x", "ao", problem="x.xml:3: <foo>\nrefused"), None, {}, alpha=ALPHA,
                       reference="mitsuba")
    assert problem.failed and problem.error == "x.xml:3: <foo> | refused"


def test_evaluate_reads_no_file(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError(f"evaluate opened {args[:1]}")

    monkeypatch.setattr(builtins, "open", refuse)
    monkeypatch.setattr(Path, "read_text", refuse)
    monkeypatch.setattr(Path, "read_bytes", refuse)
    judged = _evaluate(_tested(_batches(1, scale=1.05)), {"mitsuba": _reference(_batches(2))},
                       constants={"reflectance 0.5": 0.5})
    assert judged.failed


def test_a_failed_normals_case_notes_its_scenes_later_cases():
    cases = [ImageCase("s", "ao"), ImageCase("s", "normals"), ImageCase("s", "simple"), ImageCase("t", "ao")]
    passed = _evaluate(_tested(_batches(1)), {"mitsuba": _reference(_batches(2))})
    failed = _evaluate(_tested(_batches(1, scale=1.05)), {"mitsuba": _reference(_batches(2))})
    noted = with_scene_notes(cases, [failed, failed, passed, passed])
    assert [v.note for v in noted] == [failed.note, failed.note or GEOMETRY_NOTE, GEOMETRY_NOTE, None]
    assert [v.verdict for v in noted] == ["FAIL", "FAIL", "PASS", "PASS"]
    # A normals case that failed to render says nothing of the geometry.
    assert [v.note for v in with_scene_notes(cases[1:3], [failure("render: crashed"), passed])] == [None, None]
