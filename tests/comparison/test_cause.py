"""named_cause names a constant factor between two images (pi, pi^2, a scene's reflectance left out) and a
reference of absolute values (|n|), in one line; a difference of another kind gets no name."""
import math

import numpy as np
import pytest

from harness.comparison.cause import named_cause
from harness.comparison.summary import summarize

RNG = np.random.default_rng(7)
IMAGE = RNG.uniform(0.2, 1.0, (8, 16, 16, 3))


def _cause(test, reference, signed=False, constants=None):
    return named_cause(summarize(test), summarize(reference), signed, constants)


@pytest.mark.parametrize("factor, name", [(math.pi, "pi"), (math.pi ** 2, "pi^2"), (1 / math.pi, "1/pi"),
                                          (4 * math.pi, "4pi"), (0.5, "1/2")])
def test_a_named_factor_is_named(factor, name):
    assert _cause(IMAGE * factor, IMAGE) == f"the test is {factor:.4f}x the reference everywhere: a factor {name}"


def test_a_scenes_constant_is_named_with_what_it_means():
    cause = _cause(IMAGE * 2.0, IMAGE, constants={"reflectance 0.5": 0.5})
    assert cause.endswith("a factor 2 = 1/the reflectance 0.5 (left out?)")
    cause = _cause(IMAGE * 0.7, IMAGE, constants={"reflectance 0.7": 0.7})
    assert cause.endswith("a factor the reflectance 0.7 (applied twice?)")


def test_other_differences_get_no_name():
    assert _cause(IMAGE * 1.37, IMAGE) is None          # a constant, but none of the named ones
    ramp = np.linspace(1.0, 2 * math.pi - 1.0, 16)[None, None, :, None]  # pi on average, 1 to 5.3 across
    assert _cause(IMAGE * ramp, IMAGE) is None          # not a constant times the reference
    tinted = IMAGE * np.array([math.pi, 1.0, 1.0])
    assert _cause(tinted, IMAGE) is None                # the channels disagree


def test_a_reference_of_absolute_values_is_named_for_a_signed_image():
    normals = RNG.uniform(-1.0, 1.0, (1, 16, 16, 3)).repeat(8, axis=0)
    cause = _cause(normals, np.abs(normals), signed=True)
    assert cause.startswith("the reference holds |n|")
    assert _cause(normals, np.abs(normals), signed=False) is None
