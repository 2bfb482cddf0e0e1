"""Our scene files, made into Mitsuba scenes: each integrator mapped onto its Mitsuba equivalent
(harness/engines/mitsuba_integrators.py): the <integrator> replaced (keeping the file's `hide_emitters`),
and removed what our loader skips for that integrator (emitter types, area emitters inside shapes), a constant
emitter added where mcval's integrator assumes one, every material made white where it reads none.
A sampler Mitsuba does not have (mcval's `sobol`) becomes its closest one (MITSUBA_SAMPLER).

The film stores float32 (Mitsuba's hdrfilm default is float16). Nothing is written into the scene's folder.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from harness.engines import mitsuba_direct
from harness.engines.scene_paths import absolute_paths
from harness.engines.white_materials import white_materials
from harness.engines.written_scene import file_hide_emitters, image_integrator, integrator_type
from harness.engines.xml_lines import remove_keeping_lines, replace_keeping_lines
from harness.engines.mitsuba_integrators import mitsuba_mapping


#: Our samplers Mitsuba has no plugin of the same name for, and the Mitsuba sampler closest to each:
#: Owen-scrambled Sobol points and Mitsuba's ldsampler are both scrambled (0,2)-sequences per dimension pair.
MITSUBA_SAMPLER = {"sobol": "ldsampler"}
#: Mitsuba's scene property for Embree's robust ray-triangle test (off by default).
ROBUST = "embree_use_robust_intersections"
#: Mitsuba's integrators and their versions with the ray offset at its limit.
TIGHT_PLUGINS = {"direct": mitsuba_direct.PLUGIN}


def mitsuba_xml(text: str, integrator: str, sampler: str | None = None, tight: bool = False,
                robust: bool = False) -> str:
    """The scene text with our `integrator` mapped onto Mitsuba's plugins; `sampler`, if given, is the
    Mitsuba sampler plugin to use instead of the scene's; `tight`: `direct` becomes `mcval_direct`, the same
    integrator with its ray offset taken to the limit (harness/engines/mitsuba_direct.py); `robust`: the scene's
    embree_use_robust_intersections set (replacing a value of the file's own)."""
    mapping = mitsuba_mapping(integrator)
    root = ET.fromstring(text)
    old = [e for e in root if e.tag == "integrator"]
    # The file's own values win over the mapping's: hide_emitters always (written_scene.file_hide_emitters),
    # the others where the file's integrator is the mapped plugin itself.
    given = {"hide_emitters": file_hide_emitters(root)}
    if old and integrator_type(root, old[0]) == mapping.plugin:
        given.update({e.get("name"): e.get("value") for e in image_integrator(old[0])
                      if e.get("name") in mapping.file_values})
    plugin = TIGHT_PLUGINS.get(mapping.plugin, mapping.plugin) if tight else mapping.plugin
    new = ET.Element("integrator", type=plugin)
    for tag, name, value in mapping.properties:
        ET.SubElement(new, tag, name=name, value=given[name] if given.get(name) is not None else value)
    if mapping.add_environment and not any(e.tag == "emitter" and e.get("type") == "constant" for e in root):
        root.append(ET.Element("emitter", type="constant"))
    # Every edit keeps the lines of `text`: Mitsuba's errors name the line of the file it was given.
    if old:
        replace_keeping_lines(root, old[0], new)
        for e in old[1:]:
            remove_keeping_lines(root, e)
    else:
        root.append(new)
    for e in [e for e in root if e.tag == "emitter" and e.get("type") in mapping.drop_emitters]:
        remove_keeping_lines(root, e)
    if mapping.drop_area_emitters:
        for shape in root.iter("shape"):
            for e in [e for e in shape if e.tag == "emitter" and e.get("type") == "area"]:
                remove_keeping_lines(shape, e)
    for element in root.iter("sampler"):
        kind = sampler or element.get("type")
        element.set("type", MITSUBA_SAMPLER.get(kind, kind))
    if robust:
        for e in [e for e in root if e.get("name") == ROBUST]:
            remove_keeping_lines(root, e)
        root.append(ET.Element("boolean", name=ROBUST, value="true"))
    for film in root.iter("film"):
        for e in [e for e in film if e.get("name") == "component_format"]:
            film.remove(e)  # a file's own component_format would be a duplicate property
        ET.SubElement(film, "string", name="component_format", value="float32")
    return ET.tostring(root, encoding="unicode")


#: Mitsuba's checkerboard defaults (color0, color1).
_CHECKERBOARD = ("0.4", "0.2")


def checkerboard_opacities(root: ET.Element) -> None:
    """A finding in Mitsuba 3.9: its checkerboard read as one value (eval_1, how a mask reads its opacity) gives
    color1 where read as a colour (eval) it gives color0, and the other way round. Mitsuba's copy swaps the two
    colours of a mask's checkerboard opacity, so that Mitsuba renders the pattern the file describes, as a colour
    checkerboard draws it (in place)."""
    for mask in (b for b in root.iter("bsdf") if b.get("type") == "mask"):
        for tex in (t for t in mask if t.tag == "texture" and t.get("type") == "checkerboard"
                    and t.get("name") == "opacity"):
            given = {e.get("name"): e for e in tex if e.get("name") in ("color0", "color1")}
            for name, other, default in (("color0", "color1", _CHECKERBOARD[0]), ("color1", "color0", _CHECKERBOARD[1])):
                if name in given:
                    given[name].set("name", other)
                else:
                    ET.SubElement(tex, "float", name=other, value=default)


def load_scene(path: str | Path, integrator: str, sampler: str | None = None, tight: bool = False,
               robust: bool = False, **params):
    """Load our scene file in Mitsuba (variant already set) with `integrator` mapped (`tight`, `robust`: see
    mitsuba_xml). The translated text is loaded from memory with its file names made absolute: nothing is
    written beside the scene."""
    import mitsuba as mi

    if tight:
        mitsuba_direct.register(mi)
    path = Path(path)
    try:
        root = ET.fromstring(mitsuba_xml(path.read_text(), integrator, sampler, tight, robust))
    except ET.ParseError as e:
        raise ValueError(f"{path}: not an XML scene file ({e})") from None
    absolute_paths(root, path)  # includes inlined: the materials they hold are the scene's too
    checkerboard_opacities(root)
    if mitsuba_mapping(integrator).white_materials:
        white_materials(root)
    return mi.load_string(ET.tostring(root, encoding="unicode"), optimize=False,
                          **{k: str(v) for k, v in params.items()})
