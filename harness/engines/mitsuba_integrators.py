"""How Mitsuba 3 renders each of mcval's integrators: the plugin and properties that replace a scene's
<integrator>, what its copy of the scene must not hold, and whether it draws the integrator's own estimator.

Derived from the integrator's entry (harness/integrators/<name>.py), which names no engine: by default Mitsuba's
plugin of the same name with the entry's parameters (the scene file's own values where its <integrator> is of
that type), an `aov` entry Mitsuba's `aov` plugin, and in both the emitter kinds the integrator does not read
removed (as our loader skips them). Only an integrator whose Mitsuba counterpart has another name or other
settings is listed in OTHER_PLUGINS.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable

from harness.integrators import IntegratorEntry, entry

#: The emitter types a scene may hold at its top level (Mitsuba's names); an integrator's copy keeps those it
#: reads (IntegratorEntry.emitters). An area emitter sits inside a shape and is named "area" there.
EMITTER_TYPES = ("point", "constant", "directional", "spot", "projector", "envmap")
#: estimator_differs(scene root) -> why the mapping draws another estimator than the integrator's on this
#: scene, or None.
EstimatorCheck = Callable[[ET.Element], "str | None"]


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
    #: Every material made white and opaque (harness/engines/white_materials.py): the integrator reads none.
    white_materials: bool = False
    #: Properties whose value the scene file's own <integrator> gives when it is of type `plugin`
    #: (hide_emitters is always the file's, from any <integrator>: written_scene.file_hide_emitters).
    file_values: tuple[str, ...] = ()
    #: It draws the integrator's estimator, sample for sample (the same camera rays and the same shading
    #: estimate of each): then all the tested engine's batches alike where Mitsuba's vary are batches that
    #: ignore their seed (harness.comparison.independence_check), not an estimator without noise.
    same_estimator: bool = False
    #: Scenes on which it does not, though it does in general.
    estimator_differs: EstimatorCheck | None = None

    def summary(self) -> str:
        props = ", ".join(f"{name}={value}" for _, name, value in self.properties)
        parts = [f"{self.plugin}({props})" if props else self.plugin]
        if self.drop_emitters:
            parts.append(f"drops {', '.join(self.drop_emitters)} emitters")
        if self.drop_area_emitters:
            parts.append("drops area emitters in shapes")
        if self.add_environment:
            parts.append("adds constant emitter if none")
        if self.white_materials:
            parts.append("every material white diffuse")
        return "; ".join(parts)

    def draws_same_estimator(self, scene: Path) -> bool:
        """Whether it draws the integrator's estimator, sample for sample, on `scene`."""
        if not self.same_estimator:
            return False
        if self.estimator_differs is None:
            return True
        try:
            return self.estimator_differs(ET.parse(scene).getroot()) is None
        except ET.ParseError:
            return False


def _several_rays(root: ET.Element) -> str | None:
    """Our ao traces the file's `samples` occlusion rays per camera sample; Mitsuba's mapping one BSDF sample."""
    integrator = root.find("integrator")
    rays = next((e.get("value") for e in (integrator if integrator is not None else [])
                 if e.get("name") == "samples"), "1")
    return None if rays == "1" else f"{rays} occlusion rays per camera sample"


def _several_point_lights(root: ET.Element) -> str | None:
    """Mitsuba's one emitter sample picks one of several lights where our simple sums them all."""
    return "several point lights" if sum(e.get("type") == "point" for e in root.iter("emitter")) > 1 else None


@dataclass(frozen=True)
class _Plugin:
    """Mitsuba's counterpart of an integrator that has none of its name."""

    plugin: str
    properties: tuple[tuple[str, str, str], ...]
    same_estimator: bool
    estimator_differs: EstimatorCheck | None = None


OTHER_PLUGINS = {
    # The shading normal as an AOV; a first-hit value, the same for every engine.
    "normals": _Plugin("aov", (("string", "aovs", "nn:sh_normal"),), same_estimator=True),
    # One light sample, no BSDF sample: Mitsuba's direct integrator as our simple; the same camera rays and a
    # deterministic shading of each hit.
    "simple": _Plugin("direct", (("integer", "emitter_samples", "1"), ("integer", "bsdf_samples", "0")),
                      same_estimator=True, estimator_differs=_several_point_lights),
    # One BSDF sample and no emitter sample: the white diffuse BSDF (every material is made one) samples the
    # cosine-weighted hemisphere, so each sample is L_env * V, our ao sample for sample (Mitsuba's default adds
    # an emitter sample under MIS).
    "ao": _Plugin("direct", (("boolean", "hide_emitters", "true"), ("integer", "emitter_samples", "0"),
                             ("integer", "bsdf_samples", "1")),
                  same_estimator=True, estimator_differs=_several_rays),
}


def _drops(e: IntegratorEntry) -> dict:
    return {"drop_emitters": tuple(t for t in EMITTER_TYPES if t not in e.emitters),
            "drop_area_emitters": "area" not in e.emitters, "add_environment": e.default_environment,
            "white_materials": not e.reads_materials}


def mitsuba_mapping(integrator: str) -> MitsubaMapping:
    """How Mitsuba renders mcval's `integrator` (ValueError for one without an entry)."""
    e = entry(integrator)
    if e.same_image_as is not None:  # another estimator of that integrator's image: rendered as it, never alike
        return replace(mitsuba_mapping(e.same_image_as), same_estimator=False, estimator_differs=None)
    other = OTHER_PLUGINS.get(integrator)
    if other is not None:
        return MitsubaMapping(other.plugin, other.properties, **_drops(e), same_estimator=other.same_estimator,
                              estimator_differs=other.estimator_differs)
    if e.aov is not None:  # a first-hit value: Mitsuba's aov plugin writes it under its own name
        return MitsubaMapping("aov", (("string", "aovs", f"{e.aov}:{e.aov}"),), **_drops(e))
    # Mitsuba's plugin of the same name, with the same parameters (not mcval's own), draws the integrator's
    # estimator at their defaults.
    common = e.common_parameters()
    return MitsubaMapping(integrator, common, **_drops(e), file_values=tuple(n for _, n, _ in common),
                          same_estimator=True)
