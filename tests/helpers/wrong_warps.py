"""Known-wrong warps in numpy: the seed document's mistakes and other classic bugs.

Each is a (sample, pdf, domain) triple that the conformance checks must reject.
"""
from __future__ import annotations

import numpy as np

TWO_PI = 2 * np.pi
#: Largest double below 1: correct warps keep u there so that pdf(sample) stays positive at u = 1.
ONE_MINUS_EPS = np.nextafter(1.0, 0.0)


def _open(u):
    return np.minimum(u, ONE_MINUS_EPS)


def _direction(z, phi):
    r = np.sqrt(np.clip(1 - z * z, 0, None))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def disk_sample(u):
    r = np.sqrt(u[:, 0])
    return np.stack([r * np.cos(TWO_PI * u[:, 1]), r * np.sin(TWO_PI * u[:, 1])], axis=-1)


def disk_pdf(p):
    return np.where(np.sum(p * p, axis=1) <= 1, 1 / np.pi, 0.0)


def tent_pdf(p):
    inside = np.all(np.abs(p) <= 1, axis=1)
    return np.where(inside, (1 - np.abs(p[:, 0])) * (1 - np.abs(p[:, 1])), 0.0)


def sphere_sample(u):
    return _direction(1 - 2 * u[:, 0], TWO_PI * u[:, 1])


def hemisphere_sample(u):
    return _direction(1 - u[:, 0], TWO_PI * u[:, 1])


def hemisphere_pdf(v):
    return np.where(v[:, 2] >= 0, 1 / TWO_PI, 0.0)


def cosine_sample(u):
    return _direction(np.sqrt(1 - _open(u[:, 0])), TWO_PI * u[:, 1])


def cosine_pdf(v):
    return np.where(v[:, 2] > 0, v[:, 2] / np.pi, 0.0)


def beckmann_sample(alpha, square_alpha=True):
    def sample(u):
        a2 = alpha * alpha if square_alpha else alpha
        tan2 = -a2 * np.log1p(-_open(u[:, 1]))
        return _direction(1 / np.sqrt(1 + tan2), TWO_PI * u[:, 0])
    return sample


def beckmann_pdf(alpha, cosine_factor=True):
    def pdf(v):
        z = v[:, 2]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            tan2 = (v[:, 0] ** 2 + v[:, 1] ** 2) / (z * z)
            d = np.exp(-tan2 / alpha**2) / (np.pi * alpha**2 * z**4)
            out = d * z if cosine_factor else d
        return np.where(z > 0, np.nan_to_num(out), 0.0)
    return pdf


#: name -> (sample, pdf, domain, the check that must catch it).
WRONG = {
    # The seed document's constants.
    "seed disk pdf pi": (disk_sample, lambda p: np.where(np.sum(p * p, 1) <= 1, np.pi, 0.0), "disk",
                         "normalisation"),
    "seed sphere pdf pi/4": (sphere_sample, lambda v: np.full(len(v), np.pi / 4), "sphere", "normalisation"),
    "seed hemisphere pdf pi/2": (hemisphere_sample, lambda v: np.where(v[:, 2] >= 0, np.pi / 2, 0.0),
                                 "hemisphere", "normalisation"),
    "seed cosine pdf pi*z": (cosine_sample, lambda v: np.where(v[:, 2] > 0, np.pi * v[:, 2], 0.0), "hemisphere",
                             "normalisation"),
    # Classic bugs.
    "cosine sampler, uniform-hemisphere pdf": (cosine_sample, hemisphere_pdf, "hemisphere", "chi2"),
    "disk sampler without sqrt": (
        lambda u: np.stack([u[:, 0] * np.cos(TWO_PI * u[:, 1]), u[:, 0] * np.sin(TWO_PI * u[:, 1])], -1),
        disk_pdf, "disk", "chi2"),
    "beckmann alpha for alpha^2 (alpha 0.05)": (beckmann_sample(0.05, False), beckmann_pdf(0.05), "hemisphere",
                                                "chi2"),
    "beckmann alpha for alpha^2 (alpha 0.1)": (beckmann_sample(0.1, False), beckmann_pdf(0.1), "hemisphere",
                                               "chi2"),
    "beckmann alpha for alpha^2 (alpha 0.3)": (beckmann_sample(0.3, False), beckmann_pdf(0.3), "hemisphere",
                                               "chi2"),
    "beckmann pdf without cosine (alpha 0.3)": (beckmann_sample(0.3), beckmann_pdf(0.3, False), "hemisphere",
                                                "normalisation"),
    # (At alpha 0.01 the missing cosine changes the density by < 1e-4: no sampling test can see it.)
    "beckmann pdf without cosine (alpha 1)": (beckmann_sample(1.0), beckmann_pdf(1.0, False), "hemisphere",
                                              "normalisation"),
    "sphere sampler covering one hemisphere": (hemisphere_sample, lambda v: np.full(len(v), 1 / (4 * np.pi)),
                                               "sphere", "chi2"),
    # Domain and robustness bugs.
    "disk sampler overshooting the rim": (lambda u: 1.01 * disk_sample(u), disk_pdf, "disk", "domain"),
    "disk pdf nonzero outside the disk": (disk_sample, lambda p: np.full(len(p), 1 / np.pi), "disk", "domain"),
    "beckmann log(1-u) unguarded": (lambda u: _unguarded_beckmann(u), beckmann_pdf(0.3), "hemisphere",
                                    "hard_inputs"),
    "uniform sampler with the tent pdf": (lambda u: 2 * u - 1, tent_pdf, "tent", "chi2"),
}


def _unguarded_beckmann(u):
    # In float32, as a renderer computes it: u = 1 - 2^-53, inside [0, 1), rounds to 1 and log(1 - u) is -inf.
    # (In float64 the log only breaks at u = 1 itself, which the checks forgive: it is outside [0, 1).)
    u = u.astype(np.float32)
    with np.errstate(divide="ignore", invalid="ignore"):
        tan2 = -np.float32(0.09) * np.log(np.float32(1) - u[:, 1])
        cos = 1 / np.sqrt(1 + tan2)
        sin = np.sqrt(tan2) * cos
    phi = TWO_PI * u[:, 0]
    return np.stack([sin * np.cos(phi), sin * np.sin(phi), cos], axis=-1)
