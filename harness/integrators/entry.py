"""What the suites know of one integrator, in one place: its budgets, what of a scene it reads (emitter kinds,
parameters), its closed form on the analytic scenes (if any) and what it needs of a scene. No engine is named
here: each engine derives from these facts how it renders the integrator (Engine.integrator_mapping,
harness/engines/). Each module of this package holds one `ENTRY`."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np


#: shade(scene, points (..., 3), normals (3,) or (..., 3)) -> radiance (..., 3), at points of one surface
#: (`scene.surface`) of an analytic scene (harness/closed_forms/plane_scene.py).
Shade = Callable[[object, np.ndarray, np.ndarray], np.ndarray]
#: sample(scene, points, normals, u (..., 1) uniform in [0, 1)) -> one sample of the renderers' estimator.
Sample = Callable[[object, np.ndarray, np.ndarray, np.ndarray], np.ndarray]
#: requirement(scene root) -> None if the scene suits the integrator, else why not ("no point light").
Requirement = Callable[[ET.Element], "str | None"]
#: A parameter the integrator reads from the scene's <integrator>: (tag, name, default value as written),
#: e.g. ("integer", "emitter_samples", "1").
Parameter = tuple[str, str, str]


@dataclass(frozen=True)
class AnalyticForm:
    """The integrator's exact image of the analytic scenes of the kinds in `scenes`."""

    summary: str
    #: None: it has no closed form on a plane (`scenes` is then empty), a furnace's only.
    shade: Shade | None
    #: "plane" (a lone plane), "sphere_floor" (a sphere resting on it: analytic_sphere.py).
    scenes: tuple[str, ...] = ("plane",)
    #: Its image of a furnace (harness/closed_forms/furnace.py), furnace -> the radiance (3,) every camera ray
    #: sees; None: none.
    furnace: Callable[[object], np.ndarray] | None = None
    #: One sample of the estimator the renderers use, drawn with the closed form's exact probabilities (ao: one
    #: visibility ray, lit with probability V), or None where `shade` is noiseless per camera ray. Where a
    #: contribution is rare, all K batches of the tested engine can miss it; only a reference with the
    #: estimator's own noise lets the comparison's sample floor (harness.statistics.welch.sample_floor) see that.
    sample: Sample | None = None
    #: Whether its camera samples draw the integrator's own estimator (shaded exactly where that estimator is
    #: noiseless per camera ray, or by `sample`), so that the tested engine's noise must match it too. False:
    #: it knows the image's mean only (the noise of direct's emitter and BSDF samples is not modelled), and its
    #: comparison judges the mean, not the noise.
    draws_estimator: bool = True


@dataclass(frozen=True)
class Strategies:
    """Settings of the integrator that estimate one image with different estimators (direct: emitter sampling
    alone, BSDF sampling alone, both with MIS), which the image suite renders with the engine under test and
    compares with each other (harness/comparison/strategies.py): the one that differs is named."""

    #: (strategy, the parameters that select it, as in the scene's <integrator>), in the order compared.
    settings: tuple[tuple[str, tuple[Parameter, ...]], ...]
    #: applies(scene root, its includes inlined) -> None where every setting estimates the same image of the
    #: scene, else why not ("point lights, which BSDF sampling never finds").
    applies: Requirement


#: Rewrites that leave every integrator's image unchanged, or rotated (harness/invariance/variants.py).
GEOMETRIC_INVARIANCES = ("scale", "rotate", "translate")


@dataclass(frozen=True)
class IntegratorEntry:
    """One integrator as the harness sees it."""

    name: str
    tested_spp: int         # samples per pixel per batch of the tested engine's renders
    reference_spp: int      # samples per pixel per batch of the stored references
    #: The emitter types (the scene format's names: point, constant, area, directional, spot, projector,
    #: envmap) whose light it reads; every other emitter is ignored, so an engine removes it from its copy.
    emitters: tuple[str, ...] = ()
    #: The parameters it reads from the scene's <integrator>, with their defaults.
    parameters: tuple[Parameter, ...] = ()
    #: Those of its parameters that are mcval's own (path's `strategy`), which Mitsuba's plugin of its name does not
    #: have: Mitsuba's copy and an engine file's scene leave them out (an unknown property would fail the load).
    own_parameters: tuple[str, ...] = ()
    #: Its image is this value of the first hit, no light (an AOV, in the scene format's names: "albedo",
    #: "sh_normal"); None: it computes radiance.
    aov: str | None = None
    #: Another integrator whose image it estimates with an estimator of its own (a test-only uniform-hemisphere
    #: ao): engines render that one in its place, and never draw its estimator.
    same_image_as: str | None = None
    analytic: AnalyticForm | None = None
    requirements: tuple[tuple[str, Requirement], ...] = ()  # (summary, check)
    #: Its settings that estimate one image with different estimators, compared with each other; None: none.
    strategies: Strategies | None = None
    #: Its image may be negative (a normal's components): comparisons test no sign, maps use a signed scale.
    signed: bool = False
    #: A noiseless image of the camera and geometry alone (normals): run first on each scene, and its failure
    #: marks the scene's other cases as a camera or geometry mismatch.
    checks_geometry: bool = False
    #: The rewrites its image is linear in: "light" (every emitter scaled), "reflectance" (every diffuse
    #: reflectance scaled). The invariance suite checks that the image scales by the same factor.
    linear_in: tuple[str, ...] = ()
    #: The rewrites that leave its image unchanged though they change the scene (ao reads no material:
    #: "reflectance"). The invariance suite checks that they do.
    independent_of: tuple[str, ...] = ()
    #: It reads the scene's materials. False (ao): every surface is an opaque white diffuse one, lit on its back
    #: where its bsdf is twosided; an engine whose integrator reads them renders a copy with such materials.
    reads_materials: bool = True
    #: Its image is a direction in world space (normals): a rotated scene rotates every pixel's value.
    rotates_with_scene: bool = False
    #: Lit by a constant environment of radiance 1 where the scene has none (ao), which no rewrite scales.
    default_environment: bool = False
    #: Its estimate of a pixel changes with the seed wherever its image varies (random occlusion or light
    #: samples, or shading that changes within a pixel's footprint): an engine whose K batches are one image
    #: that varies across pixels did not use its seeds (harness/invariance/signal.py). False where a varying
    #: image can be noiseless (normals: constant over each flat surface, noisy only along its edges).
    noisy_where_varying: bool = True
    #: Its speed against error is measured by `bench` (a noiseless image has no convergence to measure).
    benchmarked: bool = True
    source: str = field(default="", compare=False)  # the file it was read from (set by the registry)

    def common_parameters(self) -> tuple[Parameter, ...]:
        """Its parameters other than its own: those the scene format's plugin of its name reads too."""
        return tuple(p for p in self.parameters if p[1] not in self.own_parameters)

    def invariances(self) -> tuple[str, ...]:
        """The invariances that apply to it: the geometric ones always, plus the rewrites it is linear in or
        independent of."""
        return GEOMETRIC_INVARIANCES + self.linear_in + self.independent_of

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
    """A requirement: at least one point emitter (the only light simple sees)."""
    return None if any(e.get("type") == "point" for e in root.iter("emitter")) else "no point light"
