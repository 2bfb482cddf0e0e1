"""A BSDF on the energy check's boundary, for its calibration: a Lambertian sampled uniformly over the hemisphere.

With albedo 1 its weights 2 cos theta_o have mean exactly 1 and a spread (variance 1/3), so the one-sided energy
check sees its null hypothesis at the edge, where its false-alarm rate is the nominal one; a BSDF that loses
energy sits below the edge and can only be conservative there. With the albedo raised it plants an excess of
known size; with its weights scaled it plants a weight defect of known size; with samples moved from the lower half
of its mass to the upper one it plants a sampler defect of known size."""
from __future__ import annotations

import numpy as np

from harness.engines.base import BsdfFunctions


def uniform_lambert(albedo: float = 1.0, weight_factor: float = 1.0, moved: float = 0.0) -> BsdfFunctions:
    """albedo / pi cos theta_o above the surface, sampled with pdf 1 / (2 pi); each weight times `weight_factor`
    (1: correct); a share `moved` of all samples taken from below cos theta_o = 1/2 (the lower half of the mass in
    cos theta) to above it, uniformly there as the pdf is (0: correct; the weights stay value / pdf)."""
    def above(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
        return (wi[:, 2] > 0) & (wo[:, 2] > 0)

    def eval_(wi, wo):
        return np.where(above(wi, wo), albedo / np.pi * wo[:, 2], 0.0)

    def pdf(wi, wo):
        return np.where(above(wi, wo), 1.0 / (2.0 * np.pi), 0.0)

    def sample(wi, u):
        z = 1.0 - u[:, 0]  # in (0, 1]: u = 0 would put wo on the horizon, where the pdf above is 0
        z = np.where((z < 0.5) & (u[:, 2] < 2.0 * moved), z + 0.5, z)  # half the samples are below: 2 moved of them
        r, phi = np.sqrt(np.maximum(0.0, 1.0 - z * z)), 2.0 * np.pi * u[:, 1]
        wo = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
        drawn = wi[:, 2] > 0
        weight = np.where(drawn, 2.0 * albedo * z * weight_factor, 0.0)
        return wo, weight, np.where(drawn, 1.0 / (2.0 * np.pi), 0.0)

    params = ({"albedo": albedo} | ({"weight_factor": weight_factor} if weight_factor != 1.0 else {})
              | ({"moved": moved} if moved else {}))
    return BsdfFunctions("uniform_lambert", params, eval_, pdf, sample)
