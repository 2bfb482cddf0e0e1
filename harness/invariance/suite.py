"""Which scenes and integrators the invariance suite renders, and how `--only` narrows them.

Four scenes that isolate what a transformation can break (a contact shadow, a closed room, slats with thin
gaps, a lone plane) at 64x64 and each integrator's own samples per pixel: both engines take about 30 s on
two cores, so `validate` can afford it. Any scene of scenes/ can be named with --only.
"""
from __future__ import annotations

from harness.images.suite import SCENES_DIR, scene_names
from harness.invariance.check import InvarianceCase
from harness.invariance.variants import INVARIANCES, Invariance

DEFAULT_SCENES = ("sphere_plane", "cornell", "crevice", "plane_point")
INTEGRATORS = ("simple", "ao", "normals")
RESOLUTION = 64


def select(only: list[str] | None, resolution: int = RESOLUTION) -> tuple[list[InvarianceCase], list[Invariance]]:
    """The cases and invariances `only` names: scene names, integrator names, scene:integrator, or
    invariance names (scale, rotate, translate, light, reflectance); a kind not named means all of it
    (scenes: the default four)."""
    from harness.integrators import entries

    only = list(only or [])
    known_scenes = scene_names()
    names = {i.name for i in INVARIANCES}
    pairs = [o.split(":", 1) for o in only if ":" in o]
    unknown = [o for o in only if ":" not in o and o not in known_scenes and o not in INTEGRATORS
               and o not in names]
    unknown += [":".join(p) for p in pairs if p[0] not in known_scenes or p[1] not in INTEGRATORS]
    if unknown:
        raise ValueError(f"unknown scene, integrator or invariance {', '.join(unknown)}: scenes are "
                         f"{', '.join(known_scenes)}; integrators {', '.join(INTEGRATORS)}; invariances "
                         f"{', '.join(i.name for i in INVARIANCES)}")
    scenes = [o for o in only if o in known_scenes] or ([] if pairs else list(DEFAULT_SCENES))
    integrators = [o for o in only if o in INTEGRATORS] or list(INTEGRATORS)
    keys = [(s, i) for s in scenes for i in integrators] + [(s, i) for s, i in pairs]
    invariances = [i for i in INVARIANCES if i.name in only] or list(INVARIANCES)
    budget = entries()
    cases = [InvarianceCase(SCENES_DIR / f"{s}.xml", i, budget[i].our_spp, resolution)
             for s, i in dict.fromkeys(keys)]
    return cases, invariances
