"""A comparison's verdict on noise: a variance beyond the noise fails against a reference that draws the same
estimator, is a warning against another one, and is not judged where the sample counts are unknown."""
import numpy as np

from harness.comparison.compare import compare_batches

K = 8


def _occlusion(seed, k=K, spp=32, size=64, weight=1.0):
    """Binary samples of value `weight` with probability p / weight: the mean p whatever the weight, the
    per-sample variance p (weight - p), larger for a larger weight (as AO sampled uniformly and weighted 2 cos)."""
    rng = np.random.default_rng(seed)
    p = np.linspace(0.05, 0.45, size)[None, :, None] * np.ones((size, 1, 3))
    return weight * rng.binomial(spp, p / weight, size=(k, size, size, 3)) / spp


def test_a_variance_beyond_the_noise_fails_against_the_same_estimator():
    c = compare_batches(_occlusion(1, weight=2.0), _occlusion(2, 16, 256), samples=(32, 256), same_estimator=True)
    assert all(s.passed for s in c.scales)  # the mean test alone passes it
    assert not c.passed and c.failed_checks == ["variance"] and c.variance.verdict == "FAIL"
    assert c.to_json()["variance"]["ratio"] > 1.5 and "the ratio must be 1" in c.variance.summary


def test_the_same_noise_passes():
    c = compare_batches(_occlusion(1), _occlusion(2, 16, 256), samples=(32, 256), same_estimator=True)
    assert c.passed and c.variance.verdict == "PASS" and abs(c.variance.result.ratio - 1) < 0.05


def test_another_estimator_with_more_noise_is_a_warning():
    c = compare_batches(_occlusion(1, weight=2.0), _occlusion(2, 16, 256), samples=(32, 256))
    assert c.passed and c.variance.verdict == "WARN" and "efficiency is lower" in c.variance.summary


def test_unknown_sample_counts_leave_the_noise_unjudged():
    c = compare_batches(_occlusion(1, weight=2.0), _occlusion(2, 16, 256), same_estimator=True)
    assert c.variance is None and "variance" not in c.failed_checks
