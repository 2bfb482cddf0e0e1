"""Which of mcval's integrators computes what a Nori integrator does (docs/engines.md#nori-scene-files), and
how the translated scene must be lit for it. Nori's own assignment integrators ignore the BSDF (albedo 1):
`simple` is one point light of power `energy` (intensity energy / 4 pi), `ao` an environment of radiance 1
that camera rays do not see. Its direct-lighting integrators read the scene's emitters and the albedo: with
point lights only they compute mcval's `simple`; with only a `distantdisk` that spans the whole sphere (thetaA
180, a constant environment) they compute mcval's `ao`, and show that environment to escaping camera rays
(Nori's sphere_ao reference image does)."""
from __future__ import annotations

from dataclasses import dataclass

#: Why a Nori integrator has no counterpart among mcval's (normals, simple, ao).
NO_EQUIVALENT = {
    "av": "average visibility samples the hemisphere uniformly along rays of a finite `length`; mcval's ao is "
          "cosine-weighted and its rays are unbounded",
    "whitted": "it follows mirror and glass paths and samples area lights, which none of mcval's integrators do",
    "path_mats": "path tracing adds indirect light, which none of mcval's integrators compute",
    "path_ems": "path tracing adds indirect light, which none of mcval's integrators compute",
    "path_mis": "path tracing adds indirect light, which none of mcval's integrators compute",
    "path": "path tracing adds indirect light, which none of mcval's integrators compute",
}
DIRECT = ("direct", "direct_ems", "direct_mats", "direct_mis")


@dataclass
class Mapping:
    """mcval's integrator for the file, and what the scene must hold for it to compute Nori's answer."""

    integrator: str
    albedo_one: bool = False          # every diffuse reflectance becomes 1 (the integrator ignores it)
    own_lights_only: bool = False     # the file's top-level emitters are dropped (the integrator ignores them)
    light_from_integrator: bool = False  # its point light is the integrator's position and energy
    unit_environment: bool = False    # its light is an environment of radiance 1
    hide_emitters: str | None = None  # kept on the written <integrator> (harness/engines/written_scene.py),
    #                                   unless the Nori integrator says otherwise (then it reads the boolean)
    why_not: str | None = None        # set: there is no mapping, and this is why


def map_integrator(kind: str, emitters: set[str]) -> Mapping:
    """The mapping for Nori's <integrator type=`kind`> in a scene whose emitters are of the kinds `emitters`
    ("point", "environment", "area")."""
    if kind == "normals":
        return Mapping("normals")
    if kind == "simple":
        return Mapping("simple", albedo_one=True, own_lights_only=True, light_from_integrator=True)
    if kind == "ao":
        return Mapping("ao", albedo_one=True, own_lights_only=True, unit_environment=True)
    if kind in DIRECT:
        if "area" in emitters:
            return Mapping("", why_not="area lights are lit by none of mcval's integrators (it models point "
                                       "lights under simple and a constant environment under ao)")
        if emitters == {"point"} and kind != "direct_mats":
            return Mapping("simple")
        if emitters == {"environment"} and kind != "direct":
            return Mapping("ao", hide_emitters="false")
        if emitters == {"point"}:
            return Mapping("", why_not="BSDF sampling never reaches a point light: the image is black")
        if not emitters:
            return Mapping("", why_not="the scene has no emitter")
        return Mapping("", why_not=f"{kind} with {' and '.join(sorted(emitters))} emitters together is no single "
                                   "integrator of mcval's (point lights: simple, a constant environment: ao)")
    return Mapping("", why_not=NO_EQUIVALENT.get(kind, "Nori has no such integrator and mcval none of that name"))
