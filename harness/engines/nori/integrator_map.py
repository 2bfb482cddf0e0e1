"""Which of mcval's integrators computes what a Nori integrator does (docs/engines.md#nori-scene-files), and
how the translated scene must be lit for it. Nori's own assignment integrators ignore the BSDF (albedo 1):
`simple` is one point light of power `energy` (intensity energy / 4 pi), `ao` an environment of radiance 1
that camera rays do not see. Its direct-lighting integrators read the scene's emitters and the albedo:
`direct_ems`, `direct_mats` and `direct_mis` are mcval's (and Mitsuba's) `direct` with one emitter sample, one
BSDF sample, or one of each under MIS, and show the emitters to camera rays (Nori's sphere_ao reference shows
its environment); `direct` (point lights, each summed exactly) is mcval's `simple`; `whitted` on a scene
without mirror or glass is `direct_ems`. Its path tracers
`path_mats`, `path_ems` and `path_mis` are mcval's `path` with the `strategy` of that name."""
from __future__ import annotations

from dataclasses import dataclass

#: Why a Nori integrator has no counterpart among mcval's (normals, simple, ao).
NO_EQUIVALENT = {
    "av": "average visibility samples the hemisphere uniformly along rays of a finite `length`; mcval's ao is "
          "cosine-weighted and its rays are unbounded",
    "whitted": "it follows mirror and glass paths, which none of mcval's integrators do (this scene has such "
               "surfaces)",
    "path": "Nori's course names its path tracers path_mats, path_ems and path_mis",
}
#: Nori's direct-lighting strategies as mcval's `direct`: (emitter_samples, bsdf_samples), one sample each.
STRATEGIES = {"direct_ems": (1, 0), "direct_mats": (0, 1), "direct_mis": (1, 1)}
#: Nori's path tracers as mcval's `path` without a depth limit, by its own `strategy` property (Mitsuba's path,
#: which has none, is "mis": the same image). Their Russian roulette differs from Mitsuba's, which changes the
#: noise, not the mean.
PATH_STRATEGIES = {"path_mats": "mats", "path_ems": "ems", "path_mis": "mis"}


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
    properties: tuple[tuple[str, str, str], ...] = ()  # (tag, name, value) on the written <integrator>
    why_not: str | None = None        # set: there is no mapping, and this is why


#: Nori's BSDFs whose Mitsuba translation is not known to be the same material: its microfacet is its course's
#: own model (a diffuse term plus a Beckmann lobe, not Mitsuba's roughplastic), and its dielectric's weights are
#: what each student writes. Only a mirror is Mitsuba's (a conductor of material "none").
UNMATCHED_BSDFS = ("microfacet", "dielectric")


def map_integrator(kind: str, emitters: set[str], specular: bool = False,
                   bsdfs: frozenset[str] = frozenset()) -> Mapping:
    """The mapping for Nori's <integrator type=`kind`> in a scene whose emitters are of the kinds `emitters`
    ("point", "environment", "area"); `specular`: whether a surface is a mirror or glass; `bsdfs`: the Nori
    BSDF types its surfaces have."""
    unmatched = sorted(set(bsdfs) & set(UNMATCHED_BSDFS))
    reads_material = kind in STRATEGIES or kind in PATH_STRATEGIES or (kind == "whitted" and not specular)
    if reads_material and unmatched:
        return Mapping("", why_not=f"it reads the material, and Nori's {' and '.join(unmatched)} has no Mitsuba "
                                   "BSDF known to be the same (its microfacet is not roughplastic)")
    if kind == "normals":
        return Mapping("normals")
    if kind == "simple":
        return Mapping("simple", albedo_one=True, own_lights_only=True, light_from_integrator=True)
    if kind == "ao":
        return Mapping("ao", albedo_one=True, own_lights_only=True, unit_environment=True)
    if kind == "whitted" and not specular:  # on diffuse surfaces: the light seen, and direct light by light samples
        kind = "direct_ems"
    if kind in STRATEGIES:
        if not emitters:
            return Mapping("", why_not="the scene has no emitter")
        if kind == "direct_mats" and emitters == {"point"}:
            return Mapping("", why_not="BSDF sampling never reaches a point light: the image is black")
        emitter_samples, bsdf_samples = STRATEGIES[kind]
        return Mapping("direct", hide_emitters="false",
                       properties=(("integer", "emitter_samples", str(emitter_samples)),
                                   ("integer", "bsdf_samples", str(bsdf_samples))))
    if kind in PATH_STRATEGIES:
        if not emitters:
            return Mapping("", why_not="the scene has no emitter")
        if kind == "path_mats" and emitters == {"point"}:
            return Mapping("", why_not="BSDF sampling never reaches a point light: the image is black")
        return Mapping("path", properties=(("string", "strategy", PATH_STRATEGIES[kind]),))
    if kind == "direct":
        if emitters == {"point"}:
            return Mapping("simple")
        return Mapping("", why_not="Nori's direct sums its point lights exactly (mcval's simple) and reads no other "
                                   "emitter; "
                                   + ("the scene has no emitter" if not emitters else
                                      f"this scene has {' and '.join(sorted(emitters - {'point'}))} emitters"))
    return Mapping("", why_not=NO_EQUIVALENT.get(kind, "Nori has no such integrator and mcval none of that name"))
