"""Which scenes and integrators the invariance suite renders, and how `--only` narrows them.

Every scene of the image suite (scenes/ and scenes/real/) with each integrator that applies to it, at 64x64
and each integrator's own samples per pixel: mcval's take about 20 s on two cores (Mitsuba's about 30 s more,
where its stored cells do not apply), so `validate` can afford all of them.
"""
from __future__ import annotations

from harness.images.suite import scene_cases, suite_integrators
from harness.integrators import IntegratorEntry, entry
from harness.invariance.cell import InvarianceCase
from harness.invariance.variants import INVARIANCES, Invariance

RESOLUTION = 64


def suite_entries(integrators=None) -> list[IntegratorEntry]:
    """The entries of the integrators the suite renders: the image suite's (the tested engine's, with an
    entry; `integrators` as suite_integrators takes them)."""
    return [entry(name) for name in suite_integrators(integrators)]


def _scenes(user=None, with_suite: bool = False) -> dict[str, object]:
    """Scene name -> file: the image suite's scenes (images.suite.scene_cases: every group, or the user's of
    --scene instead of, or with `with_suite` after, the suite's)."""
    return {c.scene: c.path for c in scene_cases(user, with_suite)}


def select(only: list[str] | None, resolution: int = RESOLUTION, integrators=None, user=None,
           with_suite: bool = False) -> tuple[list[InvarianceCase], list[Invariance]]:
    """The cases and invariances `only` names: scene names, integrator names, scene:integrator, or
    invariance names (scale, rotate, translate, light, reflectance); a kind not named means all of it.
    A scene an integrator does not apply to (simple without a point light) is left out, unless named as
    scene:integrator, which is an error saying why. `integrators`: those the tested engine renders (None:
    our renderer's); `user`, `with_suite`: the scenes of --scene (see select_cases)."""
    only = list(only or [])
    integrator_names = suite_integrators(integrators)
    scenes = _scenes(user, with_suite)
    names = {i.name for i in INVARIANCES}
    pairs = [o.split(":", 1) for o in only if ":" in o]
    unknown = [o for o in only if ":" not in o and o not in scenes and o not in integrator_names and o not in names]
    unknown += [":".join(p) for p in pairs if p[0] not in scenes or p[1] not in integrator_names]
    if unknown:
        raise ValueError(f"unknown scene, integrator or invariance {', '.join(unknown)}: scenes are "
                         f"{', '.join(scenes)}; integrators {', '.join(integrator_names)}; invariances "
                         f"{', '.join(i.name for i in INVARIANCES)}")
    for s, i in pairs:
        reason = entry(i).not_applicable(scenes[s])
        if reason:
            raise ValueError(f"{s}:{i} is not applicable: {reason}")
    chosen = [o for o in only if o in scenes] or ([] if pairs else list(scenes))
    integrators = [o for o in only if o in integrator_names] or list(integrator_names)
    keys = [(s, i) for s in chosen for i in integrators if not entry(i).not_applicable(scenes[s])]
    keys += [(s, i) for s, i in pairs]
    invariances = [i for i in INVARIANCES if i.name in only] or list(INVARIANCES)
    problems = {c.scene: c.problem for c in scene_cases(user, with_suite)}
    cases = [InvarianceCase(scenes[s], i, entry(i).tested_spp, resolution, problems[s]) for s, i in dict.fromkeys(keys)]
    return cases, invariances
