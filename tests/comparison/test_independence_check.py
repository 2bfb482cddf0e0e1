"""A comparison does not trust its mean test on batches that are not independent: it fails with that reason,
where the scales alone would pass."""
import numpy as np

from harness.comparison.compare import compare_batches, compare_summaries
from harness.comparison.summary import summarize

K = 8


def _occlusion(seed, spp=32, size=64):
    rng = np.random.default_rng(seed)
    p = np.linspace(0.05, 0.95, size)[None, :, None] * np.ones((size, 1, 3))
    return rng.binomial(spp, p, size=(K, size, size, 3)) / spp


def test_independent_batches_pass():
    c = compare_batches(_occlusion(1), _occlusion(2))
    assert c.passed and c.independence.passed
    assert c.independence.summary == "batches independent (test and reference)"


def test_a_renderer_that_ignores_its_seed_fails_as_not_independent():
    copies = np.repeat(_occlusion(1)[:1], K, axis=0)
    c = compare_batches(copies, _occlusion(2), same_estimator=True)
    assert not c.passed and c.failed_checks[0] == "independent"
    assert c.independence.summary.startswith("batches not independent: all 8 test batches are the same image")
    assert c.to_json()["independence"]["test"]["alike"]


def test_batches_all_alike_against_another_estimator_are_not_judged():
    """A noiseless estimator (cosine-weighted occlusion on a lone plane) against a noisy one of the same mean."""
    exact = np.full((K, 64, 64, 3), 0.5)
    c = compare_batches(exact, np.random.default_rng(3).binomial(32, 0.5, (K, 64, 64, 3)) / 32)
    assert c.independence.passed and not c.independence.test.alike
    assert compare_batches(exact, np.random.default_rng(3).binomial(32, 0.5, (K, 64, 64, 3)) / 32,
                           same_estimator=True).failed_checks[0] == "independent"


def test_repeating_batches_fail_where_the_scales_alone_pass():
    test = _occlusion(1)
    test[4:] = test[:4]
    c = compare_batches(test, _occlusion(2))
    assert all(s.passed for s in c.scales)  # the mean test alone would pass this
    assert not c.passed and c.failed_checks == ["independent"]
    assert "test batches" in c.independence.summary and "residual correlation 1.00" in c.independence.summary


def test_the_reference_side_is_judged_too():
    ref = _occlusion(2)
    ref[1] = ref[0]
    c = compare_batches(_occlusion(1), ref)
    assert not c.passed and not c.independence.reference.passed and c.independence.test.passed


def test_batches_alike_on_both_sides_are_a_noiseless_image():
    flat = np.full((K, 16, 16, 3), 0.5)
    c = compare_batches(flat, flat.copy())
    assert c.independence.passed and c.passed


def test_a_stored_summary_is_not_judged():
    ref = summarize(_occlusion(2))
    stored = type(ref)(ref.pixel, ref.tile, ref.image, ref.tile_size)  # as read back: no batches
    assert stored.dependence is None
    c = compare_summaries(summarize(np.repeat(_occlusion(1)[:1], K, axis=0)), stored, same_estimator=True)
    assert not c.independence.test.passed and c.independence.reference.evidence is None
