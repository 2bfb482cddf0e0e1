"""Our scene files, made into Mitsuba scenes: each of our integrators mapped onto its Mitsuba equivalent.

* normals -> ``aov`` with ``nn:sh_normal``;
* simple  -> ``direct`` with one emitter sample and no BSDF sample, the
  constant emitter removed (our simple integrator sees only point lights);
* ao      -> ``direct`` with ``hide_emitters``, the point emitters removed
  (a constant emitter of radiance 1 added when the scene has none, as ours assumes).

The film stores float32 (Mitsuba's hdrfilm default is float16).
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

INTEGRATORS = ("normals", "simple", "ao")


def mitsuba_xml(text: str, integrator: str) -> str:
    """The scene text with our `integrator` mapped onto Mitsuba's plugins."""
    if integrator not in INTEGRATORS:
        raise ValueError(f"unknown integrator {integrator!r}: expected one of {', '.join(INTEGRATORS)}")
    root = ET.fromstring(text)
    old = [e for e in root if e.tag == "integrator"]
    index = list(root).index(old[0]) if old else len(root)
    for e in old:
        root.remove(e)
    new = ET.Element("integrator")
    drop = None
    if integrator == "normals":
        new.set("type", "aov")
        ET.SubElement(new, "string", name="aovs", value="nn:sh_normal")
    elif integrator == "simple":
        new.set("type", "direct")
        ET.SubElement(new, "integer", name="emitter_samples", value="1")
        ET.SubElement(new, "integer", name="bsdf_samples", value="0")
        drop = "constant"
    else:
        new.set("type", "direct")
        ET.SubElement(new, "boolean", name="hide_emitters", value="true")
        drop = "point"
        if not any(e.tag == "emitter" and e.get("type") == "constant" for e in root):
            root.append(ET.Element("emitter", type="constant"))
    root.insert(index, new)
    for e in [e for e in root if e.tag == "emitter" and e.get("type") == drop]:
        root.remove(e)
    for film in root.iter("film"):
        ET.SubElement(film, "string", name="component_format", value="float32")
    return ET.tostring(root, encoding="unicode")


def load_scene(path: str | Path, integrator: str, **params):
    """Load our scene file in Mitsuba (variant already set) with `integrator` mapped.

    The translated file is written beside the original, so relative mesh paths
    resolve, and removed again.
    """
    import mitsuba as mi

    path = Path(path)
    tmp = path.with_name(f".tmp_{path.stem}_{integrator}_{os.getpid()}.xml")
    tmp.write_text(mitsuba_xml(path.read_text(), integrator))
    try:
        return mi.load_file(str(tmp), optimize=False, **{k: str(v) for k, v in params.items()})
    finally:
        tmp.unlink(missing_ok=True)
