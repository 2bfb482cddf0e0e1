"""The scene dialects besides Mitsuba's, as the suites see them without knowing them: how a renderer of a
dialect writes an integrator's image (Nori's: harness/engines/nori/images.py)."""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from harness.engines.nori.images import ImageConvention


def image_convention(dialect: str, integrator: str) -> ImageConvention | None:
    """How a renderer of `dialect` ("mitsuba", "nori") writes `integrator`'s image, from mcval's
    (`what` it is, `apply` to mcval's image); None where it writes mcval's."""
    if dialect != "nori":
        return None
    from harness.engines.nori.images import NORI_IMAGES
    return NORI_IMAGES.get(integrator)
