"""Numbers as both dialects write them: Nori's triples are "x, y, z" (exactly three), Mitsuba's may be one value
for all three channels; both are written back as "x, y, z" with Python's shortest round-trip repr."""
from __future__ import annotations

import math
import re

#: Nori's Color3f::getLuminance: what its tests judge of a colour.
LUMINANCE = (0.212671, 0.715160, 0.072169)

_SEPARATORS = re.compile(r"[,\s]+")


def numbers(text: str) -> list[float] | None:
    """The finite numbers in `text` (commas or spaces between them), or None if one is not a finite number."""
    try:
        values = [float(t) for t in _SEPARATORS.split(text.strip()) if t]
    except ValueError:
        return None
    return values if values and all(math.isfinite(v) for v in values) else None


def triple_text(values: list[float] | tuple[float, ...]) -> str:
    return ", ".join(number_text(v) for v in values)


def number_text(v: float) -> str:
    """`v` as short as it round-trips: 0.5 stays "0.5", 3.0 becomes "3"."""
    return str(int(v)) if float(v).is_integer() and abs(v) < 1e15 else repr(float(v))
