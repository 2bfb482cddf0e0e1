"""The suite's Mitsuba 3 scenes written in Nori's dialect, for an engine file with scene_format = "nori"
(docs/engines.md#nori-scene-files): the same scene for the integrator the case runs, so that a student's Nori
build renders what Mitsuba does. What Nori cannot express is one NoriSceneError naming the element and why."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

from harness.engines.nori import write_elements as write
from harness.engines.nori.integrator_map import STRATEGIES
from harness.engines.nori.lined_xml import LinedXml, parse_lined
from harness.engines.nori.values import number_text, triple_text
from harness.engines.scene_paths import absolute_paths
from harness.engines.written_scene import file_hide_emitters, resolve_defaults

#: The top-level elements of a suite scene; emitters other than these are used by none of mcval's integrators.
TOP_LEVEL = ("integrator", "sensor", "shape", "emitter", "bsdf")
#: A light as (its element, its position or [], its RGB intensity or radiance).
Light = tuple[ET.Element, list[float], list[float]]


def _shape_albedo(doc: LinedXml, shape: ET.Element, named: dict[str, ET.Element]) -> list[float]:
    for c in shape:
        if c.tag == "bsdf":
            return write.reflectance(c, doc.fail)
        if c.tag == "ref":
            if c.get("id") not in named:
                raise doc.fail(c, "refers to no top-level <bsdf> of that id")
            return write.reflectance(named[c.get("id")], doc.fail)
    return write.reflectance(None, doc.fail)


def _lights(doc: LinedXml, root: ET.Element, mcval_integrator: str) -> list[Light]:
    """The lights `mcval_integrator` reads, as (element, position or [], RGB value): point lights (intensity) for
    simple, constant environments (radiance, 1 where the scene has none, as mcval's ao assumes) for ao; for
    direct, both (an area light is written inside its mesh)."""
    if mcval_integrator == "direct":
        for e in root:
            if e.tag == "emitter" and e.get("type") not in ("point", "constant"):
                raise doc.fail(e, "Nori's emitters are point, area (inside a mesh) and distantdisk (a constant "
                                  "environment at thetaA 180); it has no counterpart of this one")
        points, environments = _lights(doc, root, "simple"), _lights(doc, root, "ao")
        return points + ([] if environments[0][0] is root else environments)
    kind = {"simple": "point", "ao": "constant"}.get(mcval_integrator)
    found = [e for e in root if e.tag == "emitter" and e.get("type") == kind]
    if kind == "point":
        return [(e, write.point_position(e, doc.fail), write.color(write.prop(e, "intensity"), 1, doc.fail))
                for e in found]
    if kind == "constant":
        if len(found) > 1:
            raise doc.fail(found[1], "Nori's environment is one distantdisk")
        return [(e, [], write.color(write.prop(e, "radiance"), 1, doc.fail)) for e in found] or \
            [(root, [], [1.0, 1.0, 1.0])]
    return []


def _nori_simple(doc: LinedXml, root: ET.Element, integrator: ET.Element, lights: list[Light],
                 albedos: list[list[float]]) -> None:
    """Nori's own simple integrator: one point light on the integrator (energy in W), no albedo (rho = 1):
    the shapes' common reflectance is folded into the energy, which is exact (L = rho/pi I cos / r^2)."""
    if len(lights) != 1:
        raise doc.fail(lights[1][0] if lights else root, "Nori's simple integrator has one point light")
    if any(a != albedos[0] for a in albedos):
        raise doc.fail(root, "Nori's simple integrator ignores the albedo, and these shapes differ in "
                             "reflectance: write the scene for a direct-lighting integrator instead")
    (_, position, intensity), = lights
    rho = albedos[0] if albedos else [1.0] * 3
    ET.SubElement(integrator, "point", name="position", value=triple_text(position))
    integrator.append(write.color_element("energy", [4 * math.pi * i * r for i, r in zip(intensity, rho)]))


def _nori_ao(doc: LinedXml, lights: list[Light]) -> None:
    """Nori's own ao integrator: an environment of radiance 1 that escaping camera rays do not see, and no
    material read (as mcval's ao); nothing to set."""
    if file_hide_emitters(doc.root) == "false":
        integrator = next(e for e in doc.root if e.tag == "integrator")
        raise doc.fail(integrator, "Nori's ao integrator shows nothing to a camera ray that escapes; this scene "
                                   "shows it the environment (hide_emitters false)")
    radiance = lights[0][2]
    if any(not math.isclose(r, 1.0, rel_tol=1e-6) for r in radiance):
        raise doc.fail(lights[0][0], f"Nori's ao integrator lights with radiance 1; this scene has "
                                     f"{triple_text(radiance)}")


def reads_direct_strategy(integrator: str, theirs: str) -> bool:
    """Whether a Nori build that renders mcval's `integrator` as its `theirs` is given the direct strategy a
    scene's own <integrator type="direct"> sets (_nori_direct): `theirs` is one of Nori's three."""
    return integrator == "direct" and theirs in STRATEGIES


def _nori_direct(doc: LinedXml, theirs: str) -> str:
    """The Nori integrator that draws the scene's own direct strategy, where the engine file names one of Nori's
    three (direct_ems, direct_mats, direct_mis) and the file's <integrator type="direct"> sets its samples: no
    BSDF sample is direct_ems, no emitter sample direct_mats, both direct_mis. Nori's take one of each; more
    change the noise, not the image."""
    integrator = next((e for e in doc.root if e.tag == "integrator" and e.get("type") == "direct"), None)
    if theirs not in STRATEGIES or integrator is None:
        return theirs
    given = {e.get("name"): e for e in integrator if e.tag == "integer"}
    if not {"emitter_samples", "bsdf_samples", "shading_samples"} & set(given):
        return theirs
    counts = []
    for name in ("emitter_samples", "bsdf_samples"):
        e = given.get(name, given.get("shading_samples"))
        value = "1" if e is None else e.get("value", "").strip()
        if not value.isdigit():
            raise doc.fail(e, f"{e.get('name')} must be a whole number of samples, at least 0")
        counts.append(int(value) > 0)
    if not any(counts):
        raise doc.fail(integrator, "direct needs at least one emitter or BSDF sample")
    return next(kind for kind, samples in STRATEGIES.items() if tuple(n > 0 for n in samples) == tuple(counts))


def mitsuba_to_nori(doc: LinedXml, mcval_integrator: str, theirs: str,
                    spp: int) -> tuple[ET.Element, int, int, dict[str, str]]:
    """(Nori's scene, width, height, OBJ files to write beside it) for the Mitsuba scene `doc` (defaults and
    paths resolved) rendered with mcval's integrator `mcval_integrator`, called `theirs` by the Nori build."""
    root = doc.root
    for e in root:
        if e.tag not in TOP_LEVEL:
            raise doc.fail(e, f"has no Nori counterpart (a scene written for Nori holds {', '.join(TOP_LEVEL)})")
    sensors = [e for e in root if e.tag == "sensor"]
    if len(sensors) != 1:
        raise doc.fail(sensors[1] if sensors else root, "a Nori scene has one camera")
    out = ET.Element("scene")
    sampler = ET.SubElement(out, "sampler", type="independent")
    ET.SubElement(sampler, "integer", name="sampleCount", value=str(spp))
    written_type = _nori_direct(doc, theirs) if mcval_integrator == "direct" else theirs
    integrator = ET.SubElement(out, "integrator", type=written_type)
    camera, width, height = write.camera(sensors[0], doc.fail)
    out.append(camera)
    named = {e.get("id"): e for e in root if e.tag == "bsdf" and e.get("id")}
    files: dict[str, str] = {}
    albedos = []
    for index, shape in enumerate(e for e in root if e.tag == "shape"):
        albedos.append(_shape_albedo(doc, shape, named))
        mesh, extra = write.mesh(shape, index, albedos[-1], doc.fail)
        radiance = write.area_radiance(shape, doc.fail) if mcval_integrator == "direct" else None
        if radiance is not None:  # Nori's area light: inside the mesh that emits
            ET.SubElement(mesh, "emitter", type="area").append(write.color_element("radiance", radiance))
        out.append(mesh)
        files.update(extra)
    lights = _lights(doc, root, mcval_integrator)
    if mcval_integrator == "simple" and theirs == "simple":
        _nori_simple(doc, root, integrator, lights, albedos)
    elif mcval_integrator == "ao" and theirs == "ao":
        _nori_ao(doc, lights)
    else:
        for _, position, value in lights:
            if position:  # Nori's point lights are given by their power: 4 pi I
                light = ET.SubElement(out, "emitter", type="point")
                ET.SubElement(light, "point", name="position", value=triple_text(position))
                light.append(write.color_element("power", [4 * math.pi * i for i in value]))
            else:  # an environment of constant radiance: a distant disk over the whole sphere
                light = ET.SubElement(out, "emitter", type="distantdisk")
                light.append(write.color_element("radiance", value))
                ET.SubElement(light, "float", name="thetaA", value="180")
        if mcval_integrator in ("ao", "direct"):  # whether an escaping camera ray sees the environment (ao: not)
            hide = file_hide_emitters(root) or ("true" if mcval_integrator == "ao" else "false")
            ET.SubElement(integrator, "boolean", name="hide_emitters", value=hide)
    return out, width, height, files


def written_nori_scene(path: Path, params: dict[str, str], mcval_integrator: str, theirs: str,
                       spp: int) -> tuple[str, int, int, dict[str, str]]:
    """(the Nori XML text, width, height, OBJ files by name) of the suite's scene `path` for an engine file
    with scene_format = "nori"; `params` override the scene's <default>s (res sets width and height)."""
    doc = parse_lined(Path(path).read_text(), Path(path))
    resolve_defaults(doc.root, params, str(path))
    absolute_paths(doc.root, path)
    if "res" in params:
        for sensor in doc.root.iter("sensor"):
            film = next((c for c in sensor if c.tag == "film"), None)
            if film is None:
                film = ET.SubElement(sensor, "film", type="hdrfilm")
            for e in [e for e in film if e.get("name") in ("width", "height")]:
                film.remove(e)
            for name in ("width", "height"):
                ET.SubElement(film, "integer", name=name, value=number_text(int(params["res"])))
    scene, width, height, files = mitsuba_to_nori(doc, mcval_integrator, theirs, spp)
    ET.indent(scene)
    return ET.tostring(scene, encoding="unicode") + "\n", width, height, files
