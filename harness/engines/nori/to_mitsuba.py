"""Nori's scene dialect (wjakob/nori: src/parser.cpp and the classes it makes) read as the Mitsuba 3 scene that
renders the same image, so that our renderer and Mitsuba both read a student's file. A mistake, or what has no
equivalent and changes every image, is one NoriSceneError naming the file, the element's line and why; what only
the file's own integrator uses is left out with a note (docs/engines.md#nori-scene-files)."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

from harness.engines.nori import read_elements as read
from harness.engines.nori.integrator_map import map_integrator
from harness.engines.nori.lined_xml import parse_lined
from harness.engines.nori.reader import Reader

#: Tags that only Nori's dialect has at the top of a scene (Mitsuba's are <sensor>, <shape>, a nested sampler).
NORI_TOP_LEVEL = ("camera", "mesh", "sampler")
#: What a Nori scene holds at its top level.
SCENE_CHILDREN = ("integrator", "camera", "sampler", "mesh", "emitter")


def is_nori(root: ET.Element) -> bool:
    """Whether a parsed scene file is in Nori's dialect: a <test> root, or a <scene> without Mitsuba's `version`
    attribute and with a <camera>, a <mesh> or a top-level <sampler> (which Mitsuba's files may hold too, for a
    <ref> from their sensor)."""
    return root.tag == "test" or (root.tag == "scene" and "version" not in root.attrib
                                  and any(e.tag in NORI_TOP_LEVEL for e in root))


def _one(r: Reader, root: ET.Element, tag: str, required: bool) -> ET.Element | None:
    found = [e for e in root if e.tag == tag]
    if len(found) > 1:
        raise r.fail(found[1], f"a Nori scene has one <{tag}>")
    if required and not found:
        raise r.fail(root, f"a Nori scene needs {'an' if tag[0] in 'aeiou' else 'a'} <{tag}>")
    return found[0] if found else None


#: Written for a Nori integrator that none of mcval's computes: every case of the suite names its own.
UNMATCHED_INTEGRATOR = "path"
#: The note on such an integrator says, after its place, that it is left out with these words.
NOT_COMPARED = "not compared, no integrator of mcval's computes this"


def nori_to_mitsuba(text: str, path: Path, notes: list[str] | None = None) -> ET.Element:
    """The Mitsuba 3 scene (root element) that renders what the Nori scene `text` (the file at `path`) does;
    its file names stay as Nori's, relative to the file's folder, which Mitsuba resolves the same way.

    What only the file's own integrator would use and has no counterpart (the integrator itself, a distantdisk
    narrower than the whole sphere) is left out with one line in `notes`: the suite's integrators (normals and
    ao need only the camera and the geometry) still render the scene."""
    notes = [] if notes is None else notes
    doc = parse_lined(text, Path(path))
    r, root = Reader(doc), doc.root
    if root.tag == "test":
        scenes = sum(e.tag == "scene" for e in root)
        what = (f"{scenes} one-pixel scenes, each with the value Nori's t-test expects of it" if scenes else
                "BSDFs for Nori's sampling tests, and no scene")
        raise r.fail(root, f"a Nori test file, not a scene file: it holds {what}; run its tests with `images "
                           "--nori-test` (scenes) or `bsdfs --nori-test` (BSDFs), or give a <scene> a file of its "
                           "own to compare it")
    return scene_to_mitsuba(r, root, notes)


def scene_to_mitsuba(r: Reader, root: ET.Element, notes: list[str]) -> ET.Element:
    """nori_to_mitsuba of one `<scene>` element of the file `r` reads (a scene file's root, or a scene of a test
    file): file names relative to that file's folder, what is left out added to `notes`."""
    for e in root:
        if e.tag not in SCENE_CHILDREN:
            raise r.fail(e, f"a Nori scene holds only {', '.join(SCENE_CHILDREN)}")
    integrator = _one(r, root, "integrator", required=True)
    lights = []
    for e in (e for e in root if e.tag == "emitter"):
        unmatched = read.unmatched_light(r, e)
        if unmatched:
            notes.append(unmatched)
        else:
            lights.append(read.light(r, e))
    kinds = {kind for kind, _ in lights} | {"area" for m in root if m.tag == "mesh" for e in m if e.tag == "emitter"}
    specular = any(b.get("type") in ("dielectric", "mirror") for m in root if m.tag == "mesh" for b in m
                   if b.tag == "bsdf")
    bsdfs = frozenset(b.get("type", "") for m in root if m.tag == "mesh" for b in m if b.tag == "bsdf")
    mapping = map_integrator(integrator.get("type", ""), kinds, specular, bsdfs)
    if mapping.why_not:
        notes.append(f"{r.doc.where(integrator)}: <integrator type=\"{integrator.get('type', '')}\">: {NOT_COMPARED}: "
                     f"{mapping.why_not}; the suite's integrators render the scene's camera and geometry")
        mapping = replace(mapping, integrator=UNMATCHED_INTEGRATOR)
    hide = mapping.hide_emitters
    if not mapping.light_from_integrator:  # whether camera rays see the environment: the file may say
        given = r.props(integrator, {"hide_emitters": "boolean"}).get("hide_emitters")
        if given is not None:
            hide = given.get("value", "").strip().lower()
            if hide not in ("true", "false"):
                raise r.fail(given, "hide_emitters is true or false")
    out = ET.Element("scene", version="3.0.0")
    written = ET.SubElement(out, "integrator", type=mapping.integrator)
    for tag, name, value in mapping.properties:
        ET.SubElement(written, tag, name=name, value=value)
    if hide is not None and mapping.integrator in ("ao", "direct"):  # the integrators that show emitters
        ET.SubElement(written, "boolean", name="hide_emitters", value=hide)
    out.append(read.camera(r, _one(r, root, "camera", required=True),
                           read.sampler(r, _one(r, root, "sampler", required=False))))
    out.extend([read.mesh(r, e, mapping.albedo_one) for e in root if e.tag == "mesh"])
    if mapping.light_from_integrator:
        out.append(read.integrator_light(r, integrator))
    if mapping.unit_environment:
        ao_light = ET.SubElement(out, "emitter", type="constant")
        ET.SubElement(ao_light, "rgb", name="radiance", value="1, 1, 1")
    if not mapping.own_lights_only:
        out.extend([e for _, e in lights])
    notes.extend(r.notes)
    return out
