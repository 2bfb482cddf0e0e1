"""Constant factors a mistake leaves between two quantities, named: a density divided where it should be
multiplied by pi, a solid angle of 2 pi taken for 4 pi, a factor 2 dropped. A ratio close enough to one of
them gets its name, so that a message can say "pi^2 too large" rather than quote 9.869605."""
from __future__ import annotations

import math

#: The factors recognised, each with its name: pi, pi^2, 2pi and 4pi, small integers, and their inverses.
FACTORS: tuple[tuple[str, float], ...] = (
    ("pi", math.pi), ("pi^2", math.pi ** 2), ("2pi", 2 * math.pi), ("4pi", 4 * math.pi),
    ("1/pi", 1 / math.pi), ("1/pi^2", 1 / math.pi ** 2), ("1/(2pi)", 1 / (2 * math.pi)),
    ("1/(4pi)", 1 / (4 * math.pi)), ("2", 2.0), ("1/2", 0.5), ("4", 4.0), ("1/4", 0.25),
)


def name_factor(ratio: float, tolerance: float) -> str | None:
    """The name of the factor in FACTORS that `ratio` equals within `tolerance` (relative: |ratio / factor - 1|
    at most `tolerance`), the closest if several do; None for any other ratio, and for one that is not a
    finite positive number. name_factor(9.8696, 1e-3) is "pi^2"; name_factor(1 / 9.8696, 1e-3) is "1/pi^2"."""
    try:
        ratio = float(ratio)
    except (TypeError, ValueError):
        return None
    if not (math.isfinite(ratio) and ratio > 0):
        return None
    distance, name = min((abs(ratio / value - 1.0), name) for name, value in FACTORS)
    return name if distance <= tolerance else None
