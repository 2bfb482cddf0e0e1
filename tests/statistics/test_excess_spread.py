"""excess_spread: Gaussian and binary (rare occlusion) nulls of one estimator stay below the critical ratio over
several seeds; a firefly of 10x a pixel's value in one batch is found at that pixel; a contribution that one
test batch met once where the reference met none is no excess."""
import numpy as np
import pytest

from harness.comparison.summary import summarize
from harness.statistics.excess_spread import excess_spread

K_T, K_R, N_T, N_R = 8, 16, 32, 256


def _check(test, reference, level=1e-4):
    t, r = summarize(test), summarize(reference)
    return excess_spread(t.pixel, r.pixel, t.tile, r.tile, (N_T, N_R), level)


def _gaussian(rng, k, n, shape=(48, 48, 3)):
    return rng.normal(0.5, 0.2 / np.sqrt(n), (k, *shape))


def _binary(rng, k, n, p, shape=(48, 48, 3)):
    return rng.binomial(n, p, (k, *shape)) / n


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_nulls_stay_below_the_critical_ratio(seed):
    rng = np.random.default_rng(seed)
    assert not _check(_gaussian(rng, K_T, N_T), _gaussian(rng, K_R, N_R)).rejects
    p = np.where(np.arange(48)[None, :, None] < 24, 0.5, 0.002)  # half the frame rare occlusion
    p = np.broadcast_to(p, (48, 48, 3))
    assert not _check(_binary(rng, K_T, N_T, p), _binary(rng, K_R, N_R, p)).rejects


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("factor", [10.0, 1e3, 1e30])
def test_a_firefly_is_found_where_it_is(seed, factor):
    rng = np.random.default_rng(seed)
    test = _gaussian(rng, K_T, N_T)
    test[3, 20, 30] *= factor
    e = _check(test, _gaussian(rng, K_R, N_R))
    assert e.rejects and e.worst_scale.scale == "pixel" and e.worst_scale.worst[:2] == (20, 30)


def test_a_contribution_the_reference_missed_is_no_excess():
    test = np.full((K_T, 48, 48, 3), 0.6)
    test[5, 10, 10] = 0.6 * (1 - 1 / N_T)  # one occluded sample of 32
    reference = np.full((K_R, 48, 48, 3), 0.6)
    assert not _check(test, reference).rejects
    test[5, 10, 10] = 6.0  # the same batch, 10x: a firefly
    assert _check(test, reference).rejects
