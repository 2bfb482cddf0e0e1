"""batch_outlier: Gaussian batch means are called outlying at about their level (never at OUTLIER_LEVEL over
200 nulls), one batch moved by a firefly is found with its index, and nothing is judged where the other
batches agree to rounding or there are too few."""
import numpy as np
import pytest

from harness.statistics.constants import OUTLIER_LEVEL
from harness.statistics.outlier_batch import batch_outlier


def test_gaussian_batches_stand_apart_at_their_level():
    rng = np.random.default_rng(0)
    p = np.array([batch_outlier(rng.normal(0.5, 0.01, (8, 3))).p_value for _ in range(400)])
    assert not np.any(p < OUTLIER_LEVEL)
    assert 0.0 <= np.mean(p < 0.05) <= 0.1  # Bonferroni over 24: at most its level, not far below


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("shift", [100.0, 1e4, 1e38])
def test_a_batch_moved_far_is_found(seed, shift):
    x = np.random.default_rng(seed).normal(0.5, 0.01, (8, 3))
    x[5, 1] += 0.01 * shift
    o = batch_outlier(x)
    assert o.batch == 5 and o.channel == 1 and o.p_value < OUTLIER_LEVEL


def test_nothing_is_judged_where_the_others_agree_or_batches_are_few():
    x = np.full((8, 3), 0.25)
    x[2] = 0.3  # one batch met a rare contribution: no spread of the others says how rare
    o = batch_outlier(x)
    assert o.batch != 2 and o.p_value == 1.0  # only batches whose others vary are judged: none stands apart
    assert batch_outlier(np.random.default_rng(1).normal(size=(3, 3))) is None
    assert batch_outlier(np.array([[np.nan] * 3] * 8)) is None
