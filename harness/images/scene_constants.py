"""The values in a scene file that a wrong factor between two renders may be: a diffuse reflectance, an
emitter's radiance or intensity, each where the file gives one grey value (the same in every channel). They let
a failed comparison say "1/the reflectance 0.5 (left out?)" rather than "2.0000"."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

#: The properties read, by name.
PROPERTIES = ("reflectance", "radiance", "intensity")


def _grey(value: str) -> float | None:
    """One number for "0.5" or "0.5, 0.5, 0.5" (commas or spaces); None for a colour or anything else."""
    try:
        parts = [float(p) for p in value.replace(",", " ").split()]
    except ValueError:
        return None
    return parts[0] if parts and all(p == parts[0] for p in parts) else None


def scene_constants(path: Path) -> dict[str, float]:
    """{"reflectance 0.5": 0.5, "radiance 2": 2.0, ...}: each grey value of PROPERTIES the file gives, once;
    empty for a file that does not parse (its engines say why)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return {}
    found: dict[str, float] = {}
    if any(b.get("type") == "diffuse" and not any(c.get("name") == "reflectance" for c in b)
           for b in root.iter("bsdf")):
        found["reflectance 0.5"] = 0.5  # Mitsuba's default diffuse reflectance
    for e in root.iter():
        name = e.get("name")
        if name in PROPERTIES and e.tag in ("rgb", "float", "spectrum") and e.get("value"):
            value = _grey(e.get("value", ""))
            if value is not None and value > 0:
                found.setdefault(f"{name} {value:g}", value)
    return found
