"""Named factors: each one recognised within the tolerance and not beyond it; other ratios left unnamed."""
import math

import numpy as np
import pytest

from harness.statistics.factors import FACTORS, name_factor


@pytest.mark.parametrize("name, value", FACTORS, ids=[n for n, _ in FACTORS])
def test_each_factor_is_named_within_the_tolerance_and_not_beyond(name, value):
    assert name_factor(value, 1e-3) == name
    assert name_factor(value * (1 + 9e-4), 1e-3) == name and name_factor(value * (1 - 9e-4), 1e-3) == name
    assert name_factor(value * (1 + 2e-3), 1e-3) is None and name_factor(value * (1 - 2e-3), 1e-3) is None


def test_float32_constants_are_named():
    # A float32 pi where 1/pi was meant: the seed document's disk pdf, integrated in float64.
    assert name_factor(float(np.float32(np.pi)) * math.pi, 1e-3) == "pi^2"
    assert name_factor(float(np.float32(1 / (4 * np.pi))) / (np.pi / 4), 1e-3) == "1/pi^2"


@pytest.mark.parametrize("ratio", [1.0, 1.001, 3.0, 0.9, 1.5, 6.0, 0.0, -math.pi, math.inf, math.nan])
def test_other_ratios_have_no_name(ratio):
    assert name_factor(ratio, 1e-3) is None


def test_the_closest_factor_wins_under_a_loose_tolerance():
    # pi and 4 are 27 % apart: with a tolerance of 0.3 both match 3.8 and 3.3, each closer to one of them.
    assert name_factor(3.8, 0.3) == "4" and name_factor(3.3, 0.3) == "pi"


def test_numpy_scalars_are_ratios_too():
    assert name_factor(np.float64(2 * np.pi), 1e-6) == "2pi" and name_factor(np.float32(0.5), 1e-6) == "1/2"
    assert name_factor(None, 1e-3) is None and name_factor("pi", 1e-3) is None
