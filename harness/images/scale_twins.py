"""Scale twins: suite scenes that are another scene with every length multiplied by one factor (and the point
light's intensity by its square), so that every engine must render the same image of both. Where a case has no
closed form, the reference engine's render of the twin is an oracle between the two engines: a reference that
breaks at its scale (a ray offset too large for millimetre geometry) is overruled where the tested render agrees
with the reference's own render of the twin (harness/images/oracle.py).

The pairs are those scenes/make_sphere_floor.py writes; tests/images/test_scale_twins.py checks they match it.
"""
from __future__ import annotations

from dataclasses import replace

from harness.images.suite import ImageCase

#: The source of a reference that is the reference engine's render of the case's scale twin.
SCALE_TWIN = "scale twin"
#: Scene -> its twin, among the suite's own scenes.
TWINS = {"sphere_floor_milli": "sphere_floor_unit", "sphere_floor_kilo": "sphere_floor_unit"}


def twin_case(case: ImageCase) -> ImageCase | None:
    """The case of the same integrator on the scale twin of `case`'s scene, or None (a user's scene has none)."""
    if case.group != "synthetic" or case.scene not in TWINS:
        return None
    return replace(case, scene=TWINS[case.scene], spp=None)


def twin_label(case: ImageCase, engine: str) -> str:
    """The reference's name for `engine`'s render of the twin: "mitsuba at unit scale"."""
    return f"{engine} at {TWINS[case.scene].rsplit('_', 1)[-1]} scale"
