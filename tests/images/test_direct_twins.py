"""direct's planted wrong twins (tests/cpp/direct_twins_integrator.cpp, in the test build) fail the image suite on
the rectangle-lit plane, against Mitsuba's stored reference and against the closed form, and the strategy check
points at what each got wrong; our direct passes, its strategies agreeing.

- direct_area_pdf (the light's density left in area measure): the image is 6.7 times too bright, and every pair
  of strategies disagrees. MIS weighs its light samples by about 0.97 under a light this small, so it inherits
  the defect: "ems" cannot be the odd one, and the check names ems and mis, which share the light's sampling,
  against mats.
- direct_double_mis (MIS weights that double count): twice the light; "mis" is named, ems and mats agree.
- direct_no_cosine (no cosine at the surface): 14 % too bright, alike in all three strategies, so they agree:
  only the comparisons with a reference see it.

Each case at 16 samples per pixel (the suite's 128 x 128, where the references are stored), seeded by the run.
"""
from __future__ import annotations

import dataclasses

import pytest

from harness.images.run import run_images
from harness.images.suite import select_cases
from tests.helpers.twin_engine import TwinEngine

SCENE = "plane_rect_light"
SPP = 16
TWINS = ("direct_area_pdf", "direct_double_mis", "direct_no_cosine")


@pytest.fixture(scope="module")
def results(mitsuba, tmp_path_factory):
    """The case's result per twin (and "direct" for the correct integrator), at SPP samples per pixel, seed 0."""
    (case,) = [dataclasses.replace(c, spp=SPP) for c in select_cases([f"{SCENE}:direct"])]
    out = {}
    for twin in (None, *TWINS):
        (result,), _ = run_images([case], TwinEngine("direct", twin, tmp_path_factory.mktemp("twins")), mitsuba)
        out[twin or "direct"] = result
    return out


def _ratio(result, reference: str) -> float:
    """The tested image mean over the reference's (channels averaged)."""
    return float((result.tested.batch_means.mean(axis=0) / result.references[reference].summary.image.mean).mean())


def test_our_direct_passes_and_its_strategies_agree(results):
    correct = results["direct"]
    assert correct.verdict == "PASS", correct.why
    assert set(correct.comparisons) == {"mitsuba", "analytic"} and all(c.passed for c in correct.comparisons.values())
    assert correct.strategies.verdict == "AGREE" and not correct.strategies.disagree, correct.strategies.reason
    assert correct.to_json()["strategies"]["verdict"] == "AGREE"


@pytest.mark.parametrize("twin, low, high", [("direct_area_pdf", 5.0, 9.0), ("direct_double_mis", 1.9, 2.1),
                                             ("direct_no_cosine", 1.1, 1.2)])
def test_each_twin_fails_against_mitsuba_and_the_closed_form(results, twin, low, high):
    result = results[twin]
    assert result.verdict == "FAIL"
    for reference in ("mitsuba", "analytic"):
        comparison = result.comparisons[reference]
        assert not comparison.passed and comparison.scales[-1].min_p < 1e-10, (twin, reference)
        assert low < _ratio(result, reference) < high, (twin, reference)


def test_a_light_pdf_in_area_measure_is_pinned_on_the_light_sampling(results):
    check = results["direct_area_pdf"].strategies
    assert check.disagree and check.verdict == "INCONCLUSIVE" and check.odd is None
    assert all(p.rejects for p in check.pairs)  # ems and mis both carry the defect
    assert check.suspects == ("ems", "mis") and "suspect the light's sampling or its pdf" in check.reason
    assert "strategies INCONCLUSIVE: every pair disagrees" in results["direct_area_pdf"].why


def test_double_counting_mis_weights_are_named(results):
    check = results["direct_double_mis"].strategies
    assert check.verdict == "DIFFERS" and check.odd == "mis" and check.suspects == ("mis",)
    assert not check.pair("ems", "mats").rejects
    assert results["direct_double_mis"].to_json()["strategies"]["odd"] == "mis"


def test_a_cosine_missing_from_every_strategy_is_for_the_references_to_find(results):
    check = results["direct_no_cosine"].strategies
    assert check.verdict == "AGREE", check.reason
    assert not results["direct_no_cosine"].passed
