"""Nori's two BSDF tests, judged as Nori judges them (src/chi2test.cpp, src/ttest.cpp and hypothesis.h of its
`hypothesis` library), on any BSDF of the ABI:

- chi2test: at `testCount` random incident directions (cos theta and phi uniform), `sampleCount` samples
  (default 5000 a cell) in a grid of `resolution` x 2 `resolution` cells over (cos theta_o, phi_o), a sample of
  weight 0 not counted; the expected counts are the pdf's integrals over the cells; cells sorted by expected
  count, those below `minExpFrequency` pooled (and the next ones until the pool reaches it), more than
  sampleCount 10^-5 samples in a cell expected empty a rejection; Sidak over testCount x BSDFs tests;
- ttest: at each angle (wi in the xz plane), the mean sample weight of `sampleCount` samples against the stated
  reference by Student's t (the variance floored at 10^-5, two-sided), Sidak over the references.

The BSDFs of the ABI are gray: a coloured Nori BSDF is tested through one channel (harness/commands/
nori_test_section.py maps it), as Nori's tests judge the luminance."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.bsdfs.checks import draw, incident
from harness.engines.base import BsdfFunctions
from harness.statistics.constants import sidak_level
from harness.statistics.cubature import integrate_cells
from harness.statistics.distributions import chi2_sf
from harness.statistics.nori_ttest import students_t_test
from harness.warps.checks import parameter_density
from harness.warps.domains import SPHERE


@dataclass(frozen=True)
class NoriVerdict:
    """One of Nori's tests: what it tested, its p-value and Sidak-corrected level, and Nori's message."""

    bsdf: str
    what: str  # "wi = (x, y, z)" or "angle 45"
    passed: bool
    p_value: float | None
    level: float
    message: str

    def to_json(self) -> dict:
        return {"bsdf": self.bsdf, "test": self.what, "pass": self.passed, "p_value": self.p_value,
                "level": self.level, "message": self.message}


def nori_chi2(observed: np.ndarray, expected: np.ndarray, samples: int, min_expected: float,
              level: float) -> tuple[bool, float | None, str]:
    """hypothesis::chi2_test: (passed, p-value, message)."""
    observed, expected = np.ravel(observed).astype(float), np.ravel(expected).astype(float)
    if np.any(expected < 0):
        return False, None, f"a negative expected count ({expected.min():g})"
    chi2, dof, pooled_obs, pooled_exp, pooled = 0.0, 0, 0.0, 0.0, 0
    for k in np.argsort(expected, kind="stable"):
        o, e = observed[k], expected[k]
        if e == 0:
            if o > samples * 1e-5:
                return False, None, f"{o:g} samples in a cell with expected count 0"
        elif e < min_expected or 0 < pooled_exp < min_expected:
            pooled_obs, pooled_exp, pooled = pooled_obs + o, pooled_exp + e, pooled + 1
        else:
            chi2, dof = chi2 + (o - e) ** 2 / e, dof + 1
    if pooled_exp > 0 or pooled_obs > 0:
        chi2, dof = chi2 + (pooled_obs - pooled_exp) ** 2 / pooled_exp, dof + 1
    dof -= 1
    if dof <= 0:
        return False, None, f"too few degrees of freedom ({dof})"
    p = float(chi2_sf(chi2, dof))
    passed = bool(np.isfinite(p) and p >= level)
    return passed, p, (f"chi^2 = {chi2:.6g} (d.o.f. {dof}, {pooled} cells pooled), p = {p:.4g} "
                       f"{'>=' if passed else '<'} level {level:.4g}")


def chi2test(bsdf: BsdfFunctions, wi: np.ndarray, samples: int, resolution: int, min_expected: float, level: float,
             seed: int) -> tuple[bool, float | None, str]:
    """Nori's chi2test of `bsdf` at one incident direction."""
    d = draw(bsdf, wi, samples, seed)
    counted = (d.weight != 0) & np.all(np.isfinite(d.wo), axis=1)
    s, t = SPHERE.to_param(d.wo[counted])
    rows, cols = resolution, 2 * resolution
    i = np.clip(np.floor(s * rows).astype(int), 0, rows - 1)
    j = np.clip(np.floor(t * cols).astype(int), 0, cols - 1)
    observed = np.bincount(i * cols + j, minlength=rows * cols).reshape(rows, cols)
    cells = integrate_cells(parameter_density(SPHERE, lambda w: bsdf.pdf(np.tile(wi, (len(w), 1)), w)),
                            np.linspace(0, 1, rows + 1), np.linspace(0, 1, cols + 1))
    return nori_chi2(observed, np.asarray(cells.values) * samples, samples, min_expected, level)


def random_incident(rng: np.random.Generator) -> np.ndarray:
    """Nori's chi2test's incident direction: cos theta and phi uniform."""
    cos_theta, phi = rng.random(), 2 * np.pi * rng.random()
    sin_theta = np.sqrt(max(0.0, 1 - cos_theta ** 2))
    return np.array([np.cos(phi) * sin_theta, np.sin(phi) * sin_theta, cos_theta])


def run_chi2test(bsdfs: list[BsdfFunctions], properties: dict, seed: int) -> list[NoriVerdict]:
    """Every BSDF at testCount incident directions, as Nori's chi2test runs them."""
    resolution, tests = int(properties["resolution"]), int(properties["testCount"])
    samples = int(properties["sampleCount"])
    samples = resolution * 2 * resolution * 5000 if samples < 0 else samples
    level = sidak_level(float(properties["significanceLevel"]), tests * len(bsdfs))
    rng, out = np.random.default_rng(seed), []
    for b in bsdfs:
        for _ in range(tests):
            wi = random_incident(rng)
            passed, p, message = chi2test(b, wi, samples, resolution, float(properties["minExpFrequency"]), level,
                                          int(rng.integers(2 ** 31)))
            out.append(NoriVerdict(b.label, "wi = ({:.3f}, {:.3f}, {:.3f})".format(*wi), passed, p, level, message))
    return out


def ttest(bsdf: BsdfFunctions, theta_degrees: float, reference: float, samples: int, level: float,
          seed: int) -> tuple[bool, float | None, str]:
    """Nori's ttest of `bsdf`'s mean sample weight at polar angle theta (wi in the xz plane) against `reference`."""
    weight = draw(bsdf, incident(theta_degrees), samples, seed).weight
    return students_t_test(float(np.mean(weight)), float(np.var(weight, ddof=1)), reference, samples, level)


def run_ttest(bsdfs: list[BsdfFunctions], angles: list[float], references: list[float], properties: dict,
              seed: int) -> list[NoriVerdict]:
    """Every BSDF at every angle against its reference (references in order: the first BSDF's angles, then the
    next's), as Nori's ttest runs them."""
    level = sidak_level(float(properties["significanceLevel"]), len(references))
    rng, out = np.random.default_rng(seed), []
    for k, b in enumerate(bsdfs):
        for angle, reference in zip(angles, references[k * len(angles):]):
            passed, p, message = ttest(b, angle, reference, int(properties["sampleCount"]), level,
                                       int(rng.integers(2 ** 31)))
            out.append(NoriVerdict(b.label, f"angle {angle:g}", passed, p, level, message))
    return out
