"""The scene file an engine file's renderer is given (docs/engines.md): the suite's scene with its <default>s
resolved, film size and sampler set, the integrator mapped, and file names made absolute so that the file can
be written anywhere (never into the scene's own folder)."""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

from harness.engines.scene_paths import absolute_paths

_PARAMETER = re.compile(r"\$([A-Za-z_][A-Za-z0-9_]*)")
def resolve_defaults(root: ET.Element, params: dict[str, str], source: str) -> None:
    """Every <default> of the scene removed and every $name filled in, `params` first (in place).
    ValueError naming `source` for a $name that neither gives."""
    values = {e.get("name"): e.get("value", "") for e in root if e.tag == "default"}
    values.update({k: str(v) for k, v in params.items()})
    for e in [e for e in root if e.tag == "default"]:
        root.remove(e)

    def fill(match: re.Match) -> str:
        if match.group(1) not in values:
            raise ValueError(f"{source}: ${match.group(1)} has no <default> and no value was given")
        return values[match.group(1)]

    for e in root.iter():
        for key, value in e.attrib.items():
            if "$" in value:
                e.set(key, _PARAMETER.sub(fill, value))


def image_integrator(integrator: ET.Element) -> ET.Element:
    """The <integrator> whose image `integrator` renders: itself, or the first it wraps if it is Mitsuba's `moment`
    (which adds each pixel's second moment beside that integrator's image): its properties are the file's."""
    while integrator.get("type") == "moment" and integrator.find("integrator") is not None:
        integrator = integrator.find("integrator")
    return integrator


def integrator_type(root: ET.Element, integrator: ET.Element) -> str:
    """The type of the file's <integrator> as the file's loader reads it: a $name filled from the file's
    <default>s (`type="$integrator"` with a default of path is a path integrator, and its properties are path's)."""
    values = {e.get("name"): e.get("value", "") for e in root if e.tag == "default"}
    return _PARAMETER.sub(lambda m: values.get(m.group(1), m.group(0)), image_integrator(integrator).get("type", ""))


def _set_property(parent: ET.Element, tag: str, name: str, value: str) -> None:
    for e in [e for e in parent if e.get("name") == name]:
        parent.remove(e)
    ET.SubElement(parent, tag, name=name, value=value)


def file_hide_emitters(root: ET.Element) -> str | None:
    """The `hide_emitters` value ("true"/"false") of the file's <integrator> or of one nested in it (`moment`,
    `aov`), or None. Every Mitsuba integrator reads it with one meaning, so the integrator that replaces the
    file's keeps it: ao then shows the environment to camera rays that escape (renderer/integrators/ao.cpp)."""
    for integrator in (e for e in root if e.tag == "integrator"):
        for e in integrator.iter("boolean"):
            if e.get("name") == "hide_emitters":
                return e.get("value", "").strip().lower()
    return None


def film_size(root: ET.Element) -> tuple[int, int]:
    """(width, height) of the first film, Mitsuba's defaults (768 x 576) where it says nothing."""
    film = next(root.iter("film"), None)
    size = {"width": 768, "height": 576}
    for e in (film if film is not None else ()):
        if e.get("name") in size:
            value = e.get("value", "")
            if not value.strip().lstrip("+").isdigit() or int(value) < 1:
                raise ValueError(f"the film's {e.get('name')} is {value!r}, not a whole number of pixels")
            size[e.get("name")] = int(value)
    return size["width"], size["height"]


def file_parameters(root: ET.Element, integrator: str, names: tuple[str, ...]) -> list[ET.Element]:
    """The children of the file's <integrator type="integrator"> that set one of `names` (copies): the values it
    gives mcval's integrator's parameters, written in Mitsuba's names. None (an empty list) where its <integrator> is another
    (the same names may mean something else there)."""
    own = next((e for e in root if e.tag == "integrator"), None)
    if own is None or integrator_type(root, own) != integrator:
        return []
    own = image_integrator(own)
    return [ET.Element(e.tag, name=e.get("name"), value=e.get("value", "")) for e in own if e.get("name") in names]


def written_scene(path: Path, params: dict[str, str], integrator: str, spp: int,
                  passed_on: tuple[str, tuple[str, ...]] | None = None) -> tuple[str, int, int]:
    """(the XML text, width, height) of `path` as an engine file's renderer gets it: `integrator` is the
    renderer's own name for it; `params` override the scene's <default>s (res sets width and height).
    `passed_on`: (mcval's integrator, its parameters' names): the values the file's own <integrator> of that type
    gives them are written into the renderer's (direct's emitter_samples and bsdf_samples: the strategy check's
    copies select a strategy so)."""
    root = ET.parse(path).getroot()
    resolve_defaults(root, params, str(path))
    absolute_paths(root, path)
    hide = file_hide_emitters(root)
    given = file_parameters(root, *passed_on) if passed_on else []
    for e in [e for e in root if e.tag == "integrator"]:
        root.remove(e)
    new = ET.Element("integrator", type=integrator)
    if hide is not None:
        ET.SubElement(new, "boolean", name="hide_emitters", value=hide)
    new.extend(given)
    root.insert(0, new)
    for sensor in root.iter("sensor"):
        for e in [e for e in sensor if e.tag == "sampler"]:
            sensor.remove(e)
        sampler = ET.SubElement(sensor, "sampler", type="independent")
        ET.SubElement(sampler, "integer", name="sample_count", value=str(spp))
        film = next((e for e in sensor if e.tag == "film"), None)
        if film is None:
            film = ET.SubElement(sensor, "film", type="hdrfilm")
        if "res" in params:
            _set_property(film, "integer", "width", str(params["res"]))
            _set_property(film, "integer", "height", str(params["res"]))
    width, height = film_size(root)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n", width, height
