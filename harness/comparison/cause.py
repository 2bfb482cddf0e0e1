"""What a failed comparison's difference is, when it is one a renderer's author makes: the test image a
constant times the reference (a 1/pi left out, a pdf off by pi^2, a reflectance or a light's radiance left out
or applied twice), or a signed image against one that holds its absolute value (Nori's normals integrator
writes |n|). One line, for the first line of the failure.

Public API::

    cause = named_cause(test_summary, reference_summary, signed, constants={"reflectance 0.5": 0.5})
"""
from __future__ import annotations

import numpy as np

from harness.comparison.summary import Summary
from harness.statistics.factors import name_factor

#: A constant factor is named when scaling the reference by it leaves at most this fraction of the squared
#: difference between the two mean images.
EXPLAINED = 0.1
#: ... and when the three channels' image-mean ratios agree to this (relative) and the ratio lies this close to
#: the named value.
CHANNELS_AGREE = 0.01
FACTOR_TOLERANCE = 0.005


def _absolute(test: np.ndarray, reference: np.ndarray) -> str | None:
    """The reference holds |test| (a signed image with negative values, against a non-negative one that
    |test| matches far better than test does)."""
    if not (np.any(test < 0) and np.all(reference >= 0)):
        return None
    plain, folded = (float(np.mean(np.abs(x - reference))) for x in (test, np.abs(test)))
    if not folded < EXPLAINED * plain:
        return None
    return (f"the reference holds |n|, each component's absolute value (Nori's normals integrator writes it so): "
            f"|tested| is {folded:.2g} from it on average, the tested image {plain:.2g}")


def _factor_name(ratio: float, constants: dict[str, float]) -> str | None:
    """The names `ratio` goes by: a scene's constant or its inverse, and a named factor (pi, 2pi, ...)."""
    names = []
    for what, value in constants.items():
        if value > 0 and value != 1.0:
            if abs(ratio / value - 1.0) <= FACTOR_TOLERANCE:
                names.append(f"the {what} (applied twice?)")
            elif abs(ratio * value - 1.0) <= FACTOR_TOLERANCE:
                names.append(f"1/the {what} (left out?)")
    generic = name_factor(ratio, FACTOR_TOLERANCE)
    if generic:
        names.insert(0, generic)
    return " = ".join(names) if names else None


def _factor(test: np.ndarray, reference: np.ndarray, constants: dict[str, float]) -> str | None:
    """The test image a named constant times the reference."""
    t, r = test.mean(axis=(0, 1)), reference.mean(axis=(0, 1))
    if not (np.all(r > 0) and np.all(t > 0)):
        return None
    ratios = t / r
    ratio = float(np.mean(ratios))
    if float(np.ptp(ratios)) > CHANNELS_AGREE * ratio:
        return None
    plain = float(np.sum((test - reference) ** 2))
    if not (plain > 0 and float(np.sum((test - ratio * reference) ** 2)) <= EXPLAINED * plain):
        return None
    name = _factor_name(ratio, constants)
    if name is None:
        return None
    return f"the test is {ratio:.4f}x the reference everywhere: a factor {name}"


def named_cause(test: Summary, reference: Summary, signed: bool,
                constants: dict[str, float] | None = None) -> str | None:
    """One line naming the difference between the two mean images, or None when it is none of the named
    kinds. `constants`: the scene's values a factor may be (e.g. {"reflectance 0.5": 0.5}); `signed`: the
    images may be negative (normals), so that a reference of absolute values can be recognised."""
    t, r = np.asarray(test.mean_image, np.float64), np.asarray(reference.mean_image, np.float64)
    if t.shape != r.shape or not (np.isfinite(t).all() and np.isfinite(r).all()):
        return None
    return (_absolute(t, r) if signed else None) or _factor(t, r, constants or {})
