"""Synthetic renders of the three strategies of direct lighting ("ems", "mats", "mis"): three unbiased
estimators of one image with different noise, as (K, H, W, 3) batch means, and their planted wrong twins.

- "ems": emitter sampling, light noise: Gaussian batch means, per-sample deviation a fifth of the value;
- "mats": BSDF sampling, heavy-tailed: each sample hits the light with probability p (0.02 at the image's left
  edge to 0.4 at its right) and then carries value / p, else 0 (a binomial count per batch);
- "mis": the quietest, Gaussian at a tenth of the value, with a skewed part (a gamma variate) where "mats" is
  weakest.

The image is a smooth gradient times a colour (the noise of one sample is shared by the channels, as a grey
light on coloured walls). A bias is planted as a factor 1 + b * shape over the image on one strategy's batches
(its noise scaled with it): `AREA_MEASURE` varies as a light pdf left in area measure does (cos / d^2 changes
over the floor), `DOUBLE_COUNT` is largest where both strategies' pdfs are alike, as MIS weights that sum to
more than one are, `UNIFORM` is the same everywhere. Each averages 1 over the image, so b is about the relative
bias of the image mean.

    triple = null_triple(rng, size=32, k=8, spp=32)    # {"ems": (K, H, W, 3), "mats": ..., "mis": ...}
    planted(triple, "ems", 0.1, AREA_MEASURE)
"""
from __future__ import annotations

import numpy as np

COLOUR = np.array([0.8, 0.5, 0.3])
#: The probability that a "mats" sample hits the light, at the image's left and right edges.
HITS = (0.02, 0.4)


def _image(size: int) -> np.ndarray:
    y, x = np.mgrid[0:size, 0:size] / max(size - 1, 1)
    return (0.2 + 0.8 * np.exp(-((x - 0.4) ** 2 + (y - 0.6) ** 2) / 0.3))[..., None] * COLOUR


def null_triple(rng: np.random.Generator, size: int = 32, k: int = 8, spp: int = 32,
                hits: tuple[float, float] = HITS) -> dict[str, np.ndarray]:
    """Three unbiased renders of one image: K batches of `spp` samples each, per strategy; "mats" hits the light
    with a probability from hits[0] at the left edge to hits[1] at the right."""
    truth = _image(size)
    shape = (k, size, size, 1)
    ems = truth * (1.0 + 0.2 / np.sqrt(spp) * rng.standard_normal(shape))
    p = np.linspace(*hits, size)[None, None, :, None]
    mats = truth * rng.binomial(spp, np.broadcast_to(p, shape)) / (spp * p)
    # A gamma variate of shape 2, centred and scaled to deviation 1: skewed, mean 0.
    skew = (rng.gamma(2.0, 1.0, size=shape) - 2.0) / np.sqrt(2.0)
    mis = truth * (1.0 + (0.1 * rng.standard_normal(shape) + 0.1 * (1 - 2 * p) * skew) / np.sqrt(spp))
    return {"ems": ems, "mats": mats, "mis": mis}


def uniform_shape(size: int) -> np.ndarray:
    """1 everywhere: the same relative bias in every pixel."""
    return np.ones((size, size, 1))


def area_measure_shape(size: int) -> np.ndarray:
    """From 0.5 to 1.5 down the image, as cos / d^2 varies over a floor under a light; its mean is 1, so b is
    the relative bias of the image mean."""
    y = np.mgrid[0:size, 0:size][0] / max(size - 1, 1)
    return (0.5 + y)[..., None]


def double_count_shape(size: int) -> np.ndarray:
    """Where neither strategy dominates (the middle of the image: "mats" hits the light with probability near
    0.2 there) MIS weights that double count add the most: a bump across the image, mean 1."""
    x = np.mgrid[0:size, 0:size][1] / max(size - 1, 1)
    bump = np.exp(-((x - 0.5) ** 2) / 0.08)
    return (bump / bump.mean())[..., None]


UNIFORM = uniform_shape
AREA_MEASURE = area_measure_shape
DOUBLE_COUNT = double_count_shape


def planted(triple: dict[str, np.ndarray], strategy: str, bias: float, shape=UNIFORM) -> dict[str, np.ndarray]:
    """`triple` with `strategy`'s batches scaled by 1 + bias * shape (the others as they are)."""
    size = triple[strategy].shape[1]
    return {**triple, strategy: triple[strategy] * (1.0 + bias * shape(size))}
