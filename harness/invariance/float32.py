"""What float32 cannot represent: a transformed scene whose shapes float32 cannot place, so a break of an
invariance there is a limit of the number format, not a bug of the engine.

The check reads the rewritten scene itself (not the engine's error message), so an engine cannot excuse a
failure by refusing a scene. It knows the one shape whose size the file states exactly, the sphere: float32
rounds a coordinate x to within spacing(x)/2, about |x| * 6e-8, so a point on a sphere of radius R centred
at largest coordinate C is off the surface by up to C * 6e-8. Below R = 1e-4 C that is over 6e-4 R, which
the nearly noiseless images of the suite resolve (its tile means move by about that much).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from harness.closed_forms.plane_scene import NotAnalytic, sphere_geometry

#: Smallest sphere radius over its centre's largest coordinate that float32 represents (see above).
MIN_RADIUS_TO_CENTRE = 1e-4


def float32_limit(scene: Path) -> str | None:
    """Why float32 cannot represent `scene` (a rewritten scene, no $parameters in its shapes), or None."""
    for shape in ET.parse(scene).getroot().iter("shape"):
        if shape.get("type") != "sphere":
            continue
        try:
            centre, radius = sphere_geometry(shape)
        except (NotAnalytic, ValueError):
            continue  # an ellipsoid or a parameter: the engine's own checks apply
        largest = float(np.max(np.abs(centre)))
        if radius < MIN_RADIUS_TO_CENTRE * largest:
            spacing = float(np.spacing(np.float32(largest)))
            return (f"not representable in float32: a sphere of radius {radius:.3g} centred at largest coordinate "
                    f"{largest:.4g}, where float32's spacing is {spacing:.2g} ({spacing / radius:.2g} of the radius); "
                    f"a sphere needs a radius of at least {MIN_RADIUS_TO_CENTRE:g} times that coordinate, so this "
                    f"starts once the centre is {radius / MIN_RADIUS_TO_CENTRE:.3g} ({1 / MIN_RADIUS_TO_CENTRE:g} "
                    f"radii) from the origin along an axis")
    return None
