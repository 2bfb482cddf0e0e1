"""The invariances: each a rewrite of a scene and what it must do to each integrator's image.

A variant's image, mapped back by `expected` (divided by its factor, or its normals rotated back), must
equal the base scene's image. The camera moves with the scene, so the comparison is pixel by pixel.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.invariance.rewrite import rotation_matrix

#: The rotation: a unit axis off every coordinate plane, by an angle that is no multiple of 90 degrees.
ROTATION_AXIS = tuple(np.array([0.3, 1.0, 0.2]) / np.linalg.norm([0.3, 1.0, 0.2]))
ROTATION_DEGREES = 37.0
#: The translation: float32 rounds a moved scene's coordinates to its spacing there, which the nearly
#: noiseless direct-light images resolve. Measured at 64x64 (sphere_plane, cornell, crevice): our renderer
#: fails at (1e2, -2e2, 3e2) (tile means 1e-4 off) and beyond, passes at (3e1, -6e1, 9e1) and below.
TRANSLATION = (10.0, -20.0, 30.0)
SCALES = (1e-3, 1e3)


@dataclass(frozen=True)
class Variant:
    """One rewritten scene: (kind, value) for harness.invariance.rewrite, and its label."""

    invariance: str
    kind: str
    value: object
    label: str

    def expected(self, integrator: str, batches: np.ndarray) -> np.ndarray:
        """The variant's batches mapped back onto what the base scene's must be."""
        if integrator == "normals":
            if self.kind == "rotate":
                r = rotation_matrix(*self.value)[:3, :3]
                return batches @ r  # each pixel's n' = R n, so n = R^T n' (rows: n'^T R)
            return batches
        if self.kind in ("light", "reflectance"):
            return batches / float(self.value)
        return batches


@dataclass(frozen=True)
class Invariance:
    name: str
    summary: str
    variants: tuple[Variant, ...]
    #: Integrators whose image it can change (the rest would compare an image with itself in effect).
    integrators: tuple[str, ...]


def _scale_label(s: float) -> str:
    return f"x{s:g}"


INVARIANCES = (
    Invariance("scale", "everything scaled by s about the origin (point intensity x s^2, clip distances x s): "
                        "image unchanged",
               tuple(Variant("scale", "scale", s, _scale_label(s)) for s in SCALES), ("simple", "ao", "normals")),
    Invariance("rotate", f"everything rotated by {ROTATION_DEGREES:g} degrees about the unit axis "
                         f"({', '.join(f'{c:.3f}' for c in ROTATION_AXIS)}): image unchanged, normals rotated",
               (Variant("rotate", "rotate", (ROTATION_AXIS, ROTATION_DEGREES), f"{ROTATION_DEGREES:g} deg"),),
               ("simple", "ao", "normals")),
    Invariance("translate", f"everything moved by {TRANSLATION}: image unchanged",
               (Variant("translate", "translate", TRANSLATION, "+(" + ", ".join(f"{c:g}" for c in TRANSLATION) + ")"),),
               ("simple", "ao", "normals")),
    Invariance("light", "every emitter's intensity or radiance x 2: image x 2",
               (Variant("light", "light", 2.0, "x2"),), ("simple", "ao")),
    Invariance("reflectance", "every diffuse reflectance x 1/2: image x 1/2",
               (Variant("reflectance", "reflectance", 0.5, "x0.5"),), ("simple", "ao")),
)


def invariance(name: str) -> Invariance:
    for inv in INVARIANCES:
        if inv.name == name:
            return inv
    raise ValueError(f"unknown invariance {name!r}: known are {', '.join(i.name for i in INVARIANCES)}")
