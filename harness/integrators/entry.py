"""What the harness knows of one integrator, in one place: its budgets, its Mitsuba equivalent, its closed
form on the analytic scenes (if any) and what it needs of a scene. Each module of this package holds one `ENTRY`."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class MitsubaMapping:
    """How a scene file's <integrator> is replaced for Mitsuba, and what Mitsuba must not see.

    What is removed is exactly what our loader skips for this integrator, so both render the same scene.
    """

    plugin: str                                    # Mitsuba's integrator type
    properties: tuple[tuple[str, str, str], ...] = ()  # (tag, name, value) children of <integrator>
    drop_emitters: tuple[str, ...] = ()            # top-level <emitter type> removed
    drop_area_emitters: bool = False               # <emitter type="area"> inside shapes removed
    add_environment: bool = False                  # a constant emitter (radiance 1) when the scene has none

    def summary(self) -> str:
        props = ", ".join(f"{name}={value}" for _, name, value in self.properties)
        parts = [f"{self.plugin}({props})" if props else self.plugin]
        if self.drop_emitters:
            parts.append(f"drops {', '.join(self.drop_emitters)} emitters")
        if self.drop_area_emitters:
            parts.append("drops area emitters in shapes")
        if self.add_environment:
            parts.append("adds constant emitter if none")
        return "; ".join(parts)


#: Mitsuba's emitter types that none of our integrators uses: our loader skips them, so Mitsuba must not see
#: them either (renderer/scene_loader.cpp, isOtherEmitter).
UNUSED_EMITTERS = ("directional", "spot", "projector", "envmap")


#: shade(scene, points (..., 3), normals (3,) or (..., 3)) -> radiance (..., 3), at points of one surface
#: (`scene.surface`) of an analytic scene (harness/closed_forms/plane_scene.py).
Shade = Callable[[object, np.ndarray, np.ndarray], np.ndarray]
#: sample(scene, points, normals, u (..., 1) uniform in [0, 1)) -> one sample of the renderers' estimator.
Sample = Callable[[object, np.ndarray, np.ndarray, np.ndarray], np.ndarray]
#: requirement(scene root) -> None if the scene suits the integrator, else why not ("no point light").
Requirement = Callable[[ET.Element], "str | None"]
#: estimator_differs(scene root) -> why Mitsuba's mapping draws another estimator than ours on this scene, or None.
EstimatorCheck = Callable[[ET.Element], "str | None"]


@dataclass(frozen=True)
class AnalyticForm:
    """The integrator's exact image of the analytic scenes of the kinds in `scenes`."""

    summary: str
    shade: Shade
    #: "plane" (a lone plane), "sphere_floor" (a sphere resting on it: analytic_sphere.py).
    scenes: tuple[str, ...] = ("plane",)
    #: One sample of the estimator the renderers use, drawn with the closed form's exact probabilities (ao: one
    #: visibility ray, lit with probability V), or None where `shade` is noiseless per camera ray. Where a
    #: contribution is rare, all K batches of ours can miss it; only a reference with the estimator's own noise
    #: lets the comparison's sample floor (harness.statistics.welch.sample_floor) see that.
    sample: Sample | None = None


#: Rewrites that leave every integrator's image unchanged, or rotated (harness/invariance/variants.py).
GEOMETRIC_INVARIANCES = ("scale", "rotate", "translate")


@dataclass(frozen=True)
class ImageConvention:
    """Another renderer's way of writing an integrator's image, from ours."""

    what: str  # e.g. "|n|, each component's absolute value"
    apply: Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class IntegratorEntry:
    """One integrator as the harness sees it."""

    name: str
    our_spp: int            # samples per pixel per batch of our renders
    reference_spp: int      # samples per pixel per batch of stored Mitsuba references
    mitsuba: MitsubaMapping
    analytic: AnalyticForm | None = None
    requirements: tuple[tuple[str, Requirement], ...] = ()  # (summary, check)
    #: Its image may be negative (a normal's components): comparisons test no sign, maps use a signed scale.
    signed: bool = False
    #: A noiseless image of the camera and geometry alone (normals): run first on each scene, and its failure
    #: marks the scene's other cases as a camera or geometry mismatch.
    checks_geometry: bool = False
    #: The rewrites its image is linear in: "light" (every emitter scaled), "reflectance" (every diffuse
    #: reflectance scaled). The invariance suite checks that the image scales by the same factor.
    linear_in: tuple[str, ...] = ()
    #: Its image is a direction in world space (normals): a rotated scene rotates every pixel's value.
    rotates_with_scene: bool = False
    #: Lit by a constant environment of radiance 1 where the scene has none (ao), which no rewrite scales.
    default_environment: bool = False
    #: Its Mitsuba mapping draws the same estimator, sample for sample (the same camera rays and the same
    #: shading estimate of each): then all our batches alike where Mitsuba's vary are batches that ignore their
    #: seed (harness.comparison.independence_check), not an estimator without noise.
    same_estimator_in_mitsuba: bool = False
    #: Scenes on which it does not, though it does in general (see `same_estimator`).
    estimator_differs: EstimatorCheck | None = None
    #: Its estimate of a pixel changes with the seed wherever its image varies (random occlusion or light
    #: samples, or shading that changes within a pixel's footprint): an engine whose K batches are one image
    #: that varies across pixels did not use its seeds (harness/invariance/signal.py). False where a varying
    #: image can be noiseless (normals: constant over each flat surface, noisy only along its edges).
    noisy_where_varying: bool = True
    #: Its speed against error is measured by `bench` (a noiseless image has no convergence to measure).
    benchmarked: bool = True
    #: How Nori's integrator of this name writes the image, from ours (normals: |n|); None: as ours. A reference
    #: image of a scene in Nori's dialect is compared with ours so written.
    nori_image: ImageConvention | None = None
    source: str = field(default="", compare=False)  # the file it was read from (set by the registry)

    def invariances(self) -> tuple[str, ...]:
        """The invariances that apply to it: the geometric ones always, plus the rewrites it is linear in."""
        return GEOMETRIC_INVARIANCES + self.linear_in

    def same_estimator(self, scene: Path) -> bool:
        """Whether Mitsuba's mapping draws our estimator, sample for sample, on `scene`."""
        if not self.same_estimator_in_mitsuba:
            return False
        if self.estimator_differs is None:
            return True
        try:
            return self.estimator_differs(ET.parse(scene).getroot()) is None
        except ET.ParseError:
            return False

    def not_applicable(self, scene: Path) -> str | None:
        """Why `scene` cannot be rendered with this integrator, or None if it can."""
        try:
            root = ET.parse(scene).getroot()
        except ET.ParseError:
            return None  # the renderer's loader reports a broken file, with its line, as the case's failure
        for _, check in self.requirements:
            reason = check(root)
            if reason:
                return reason
        return None


def has_point_light(root: ET.Element) -> str | None:
    """A requirement: at least one point emitter (the only light our direct-lighting integrator sees)."""
    return None if any(e.get("type") == "point" for e in root.iter("emitter")) else "no point light"
