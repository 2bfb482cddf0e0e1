"""Error metrics: FLIP is safe on any reference magnitude."""
import numpy as np
import pytest

from harness.comparison.metrics import flip_map


@pytest.mark.parametrize("scale", [1e-30, 1e-6, 1e6])
def test_hdr_flip_does_not_depend_on_a_common_scale(scale):
    """HDR-FLIP places its exposures by the reference: scaling both images changes nothing, and a
    reference of 1e-30 (which made flip_evaluator exit the process) is just another scale."""
    rng = np.random.default_rng(0)
    ref = rng.random((16, 16, 3)).astype(np.float32) * 3
    test = ref * 1.05
    assert flip_map(test * scale, ref * scale)[1] == pytest.approx(flip_map(test, ref)[1], rel=1e-4)


def test_hdr_flip_of_a_black_reference_is_nan_not_a_crash():
    error, mean = flip_map(np.ones((8, 8, 3)), np.zeros((8, 8, 3)))
    assert np.isnan(mean) and np.isnan(error).all()
