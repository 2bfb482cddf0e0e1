"""The invariances: each a rewrite of a scene and what it must do to each integrator's image.

A variant's image, mapped back by `expected` (divided by its factor, or its normals rotated back), must
equal the base scene's image. The camera moves with the scene, so the comparison is pixel by pixel.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.integrators.entry import IntegratorEntry
from harness.invariance.rewrite import rotation_matrix

#: The rotation: a unit axis off every coordinate plane, by an angle that is no multiple of 90 degrees.
ROTATION_AXIS = tuple(np.array([0.3, 1.0, 0.2]) / np.linalg.norm([0.3, 1.0, 0.2]))
ROTATION_DEGREES = 37.0
#: The translation, and how far translations reach before float32 gives out (measured at 64x64 on
#: sphere_plane, cornell and crevice with our renderer).
TRANSLATION = (10.0, -20.0, 30.0)
_HOLDS, _BREAKS = (30.0, -60.0, 90.0), (100.0, -200.0, 300.0)


def _spacing(v) -> float:
    return float(np.spacing(np.float32(max(abs(c) for c in v))))


TRANSLATION_REACH = (
    f"The check moves every scene by {TRANSLATION}: float32's spacing at its largest coordinate is "
    f"{_spacing(TRANSLATION):.2g}. Our renderer also holds at {_HOLDS} (spacing {_spacing(_HOLDS):.2g}); from "
    f"{_BREAKS} on (spacing {_spacing(_BREAKS):.2g}) float32's rounding of the moved scene's own vertices, a few "
    f"1e-5 of these unit-sized scenes, moves tile means by about 1e-4, which the nearly noiseless direct-light "
    f"images resolve. A translation stops being representable for a scene between those spacings, about 1e-5 "
    f"of its size; for smaller features (sphere_floor_milli's sphere) sooner, as the FLOAT32 cells say.")
SCALES = (1e-3, 1e3)


@dataclass(frozen=True)
class Variant:
    """One rewritten scene: (kind, value) for harness.invariance.rewrite, and its label."""

    invariance: str
    kind: str
    value: object
    label: str

    def expected(self, entry: IntegratorEntry, batches: np.ndarray, has_environment: bool = True) -> np.ndarray:
        """The variant's batches mapped back onto what the base scene's must be, for the integrator of `entry`.
        `has_environment`: the base scene has a constant emitter (without one, an integrator with a default
        environment lights with a fixed radiance 1 the rewrite cannot scale)."""
        if self.kind == "rotate" and entry.rotates_with_scene:
            r = rotation_matrix(*self.value)[:3, :3]
            return batches @ r  # each pixel's n' = R n, so n = R^T n' (rows: n'^T R)
        if self.kind == "light" and entry.default_environment and not has_environment:
            return batches
        if self.kind in entry.linear_in:
            return batches / float(self.value)
        return batches


@dataclass(frozen=True)
class Invariance:
    name: str
    summary: str
    variants: tuple[Variant, ...]

    def applies_to(self, entry: IntegratorEntry) -> bool:
        """Whether it can change the integrator's image (else it would compare an image with itself)."""
        return self.name in entry.invariances()


def _scale_label(s: float) -> str:
    return f"x{s:g}"


INVARIANCES = (
    Invariance("scale", "everything scaled by s about the origin (point intensity x s^2, clip distances x s): "
                        "image unchanged",
               tuple(Variant("scale", "scale", s, _scale_label(s)) for s in SCALES)),
    Invariance("rotate", f"everything rotated by {ROTATION_DEGREES:g} degrees about the unit axis "
                         f"({', '.join(f'{c:.3f}' for c in ROTATION_AXIS)}): image unchanged, normals rotated",
               (Variant("rotate", "rotate", (ROTATION_AXIS, ROTATION_DEGREES), f"{ROTATION_DEGREES:g} deg"),)),
    Invariance("translate", f"everything moved by {TRANSLATION}: image unchanged",
               (Variant("translate", "translate", TRANSLATION, "+(" + ", ".join(f"{c:g}" for c in TRANSLATION) + ")"),)),
    Invariance("light", "every emitter's intensity or radiance x 2: image x 2 (ao without a constant emitter "
                        "lights with a fixed radiance 1: unchanged)",
               (Variant("light", "light", 2.0, "x2"),)),
    Invariance("reflectance", "every diffuse reflectance x 1/2: image x 1/2 (ao reads no material: unchanged)",
               (Variant("reflectance", "reflectance", 0.5, "x0.5"),)),
)


def invariance(name: str) -> Invariance:
    for inv in INVARIANCES:
        if inv.name == name:
            return inv
    raise ValueError(f"unknown invariance {name!r}: known are {', '.join(i.name for i in INVARIANCES)}")
