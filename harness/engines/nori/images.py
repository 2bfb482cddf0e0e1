"""How Nori's integrators write their images, where they differ from mcval's of the same name: a reference
image of a scene in Nori's dialect is compared with the tested engine's image so written."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class ImageConvention:
    """Another renderer's way of writing an integrator's image, from mcval's."""

    what: str  # e.g. "|n|, each component's absolute value"
    apply: Callable[[np.ndarray], np.ndarray]


#: Nori's integrators whose image is not mcval's: its tutorial normals integrator returns the normal's
#: absolute value, component by component.
NORI_IMAGES = {"normals": ImageConvention("|n|, each component's absolute value", np.abs)}
