"""Nori's scene elements, one function each, read as Mitsuba 3's (harness/engines/nori/to_mitsuba.py). Every
default is Nori's, stated where it is read."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from harness.engines.nori.reader import Reader, obj_has_normals, rgb
from harness.engines.nori.values import number_text, triple_text

#: Mitsuba's gaussian has no radius of its own: it is 4 stddev (src/rfilters/gaussian.cpp); its box is 0.5
#: wide and its mitchell 2 (box.cpp, mitchell.cpp), as Nori's defaults are.
GAUSSIAN_RADIUS_IN_STDDEVS = 4.0


def rfilter(r: Reader, e: ET.Element | None) -> ET.Element:
    """Nori's filter (default: gaussian, radius 2, stddev 0.5, src/perspective.cpp) as Mitsuba's."""
    kind = "gaussian" if e is None else e.get("type")
    out = ET.Element("rfilter", type=kind)
    if kind == "gaussian":
        p = r.props(e, {"radius": "float", "stddev": "float"}) if e is not None else {}
        stddev = r.number(p.get("stddev"), 0.5, low=1e-6)
        radius = r.number(p.get("radius"), 2.0, low=0)
        if not math.isclose(radius, GAUSSIAN_RADIUS_IN_STDDEVS * stddev, rel_tol=1e-6):
            raise r.fail(p.get("radius", e), f"Mitsuba's gaussian always reaches 4 stddev; radius {radius:g} "
                                             f"with stddev {stddev:g} has no equivalent")
        ET.SubElement(out, "float", name="stddev", value=number_text(stddev))
    elif kind == "box":
        r.props(e, {})
    elif kind == "tent":
        p = r.props(e, {"radius": "float"})
        ET.SubElement(out, "float", name="radius", value=number_text(r.number(p.get("radius"), 1.0, low=1e-6)))
    elif kind == "mitchell":
        p = r.props(e, {"radius": "float", "B": "float", "C": "float"})
        if r.number(p.get("radius"), 2.0) != 2.0:
            raise r.fail(p["radius"], "Mitsuba's mitchell filter is 2 pixels wide, always")
        for name in ("B", "C"):
            ET.SubElement(out, "float", name=name, value=number_text(r.number(p.get(name), 1 / 3)))
    else:
        raise r.fail(e, "Nori's filters are gaussian, box, tent and mitchell")
    return out


def sampler(r: Reader, e: ET.Element | None) -> ET.Element:
    """Nori's top-level sampler (default: independent, sampleCount 1, src/independent.cpp), for the sensor."""
    if e is not None and e.get("type") != "independent":
        raise r.fail(e, "Nori's sampler is independent (a student's other samplers have no agreed meaning)")
    p = r.props(e, {"sampleCount": "integer"}) if e is not None else {}
    count = r.number(p.get("sampleCount"), 1, low=1)
    if not count.is_integer():
        raise r.fail(p["sampleCount"], "sampleCount must be a whole number")
    out = ET.Element("sampler", type="independent")
    ET.SubElement(out, "integer", name="sample_count", value=str(int(count)))
    return out


def camera(r: Reader, e: ET.Element, sampler_element: ET.Element) -> ET.Element:
    """Nori's perspective camera (src/perspective.cpp) as Mitsuba's sensor: fov is horizontal (default 30),
    nearClip 1e-4, farClip 1e4, 1280 x 720 pixels."""
    if e.get("type") != "perspective":
        raise r.fail(e, "Nori's camera is perspective")
    p = r.props(e, {"fov": "float", "nearClip": "float", "farClip": "float", "width": "integer",
                    "height": "integer", "toWorld": "transform"}, objects=("rfilter",))
    filters = [c for c in e if c.tag == "rfilter"]
    if len(filters) > 1:
        raise r.fail(filters[1], "a camera has one reconstruction filter")
    fov = r.number(p.get("fov"), 30.0)
    if not 0 < fov < 180:
        raise r.fail(p["fov"], "fov must be between 0 and 180 degrees")
    near, far = r.number(p.get("nearClip"), 1e-4, low=0), r.number(p.get("farClip"), 1e4, low=0)
    if not 0 < near < far:
        raise r.fail(e, f"expected 0 < nearClip < farClip (got {near:g}, {far:g})")
    size = {}
    for name, default in (("width", 1280), ("height", 720)):
        v = r.number(p.get(name), default, low=1)
        if not v.is_integer():
            raise r.fail(p[name], f"{name} must be a whole number of pixels")
        size[name] = int(v)
    out = ET.Element("sensor", type="perspective")
    ET.SubElement(out, "float", name="fov", value=number_text(fov))
    ET.SubElement(out, "string", name="fov_axis", value="x")
    ET.SubElement(out, "float", name="near_clip", value=number_text(near))
    ET.SubElement(out, "float", name="far_clip", value=number_text(far))
    out.extend(r.transform(p.get("toWorld")))
    out.append(sampler_element)
    film = ET.SubElement(out, "film", type="hdrfilm")
    for name, value in size.items():
        ET.SubElement(film, "integer", name=name, value=str(value))
    ET.SubElement(film, "string", name="pixel_format", value="rgb")
    film.append(rfilter(r, filters[0] if filters else None))
    return out


def bsdf(r: Reader, e: ET.Element | None, albedo_one: bool) -> ET.Element:
    """Nori's diffuse BSDF (albedo, default 0.5, src/diffuse.cpp) as Mitsuba's; albedo 1 where the integrator
    ignores it."""
    if e is not None and e.get("type") in OTHER_BSDFS:
        return _other_bsdf(r, e)
    if e is not None and e.get("type") != "diffuse":
        raise r.fail(e, f"Nori's BSDFs are diffuse, {', '.join(OTHER_BSDFS)}")
    p = r.props(e, {"albedo": "color"}) if e is not None else {}
    out = ET.Element("bsdf", type="diffuse")
    out.append(rgb("reflectance", [1.0] * 3 if albedo_one else r.color(p.get("albedo"), 0.5)))
    return out


#: Nori's other BSDFs (src/microfacet.cpp, dielectric.cpp, mirror.cpp): what each reads, with its default, and
#: Mitsuba's BSDF of that surface with the name of each value there.
OTHER_BSDFS = {
    "microfacet": ("roughplastic", {"alpha": ("float", 0.1, "alpha"), "intIOR": ("float", 1.5046, "int_ior"),
                                    "extIOR": ("float", 1.000277, "ext_ior"),
                                    "kd": ("color", 0.5, "diffuse_reflectance")}),
    "dielectric": ("dielectric", {"intIOR": ("float", 1.5046, "int_ior"), "extIOR": ("float", 1.000277, "ext_ior")}),
    "mirror": ("conductor", {}),
}


def _other_bsdf(r: Reader, e: ET.Element) -> ET.Element:
    """A Nori BSDF other than diffuse as Mitsuba's of the same kind. None of mcval's integrators models it:
    normals and ao do not read it, simple refuses it (the engines say so), and direct and path read the mirror
    only (integrator_map.UNMATCHED_BSDFS)."""
    kind, reads = OTHER_BSDFS[e.get("type")]
    p = r.props(e, {name: tag for name, (tag, _, _) in reads.items()})
    out = ET.Element("bsdf", type=kind)
    if kind == "roughplastic":
        ET.SubElement(out, "string", name="distribution", value="beckmann")
    if kind == "conductor":
        ET.SubElement(out, "string", name="material", value="none")
    for name, (tag, default, mitsuba) in reads.items():
        if tag == "color":
            out.append(rgb(mitsuba, r.color(p.get(name), default)))
        else:
            ET.SubElement(out, "float", name=mitsuba, value=repr(r.number(p.get(name), default, low=0.0)))
    return out


def area_emitter(r: Reader, e: ET.Element) -> ET.Element:
    """An area light on a mesh (radiance, an RGB colour) as Mitsuba's area emitter."""
    if e.get("type") != "area":
        raise r.fail(e, "an emitter inside a mesh is an area light (type=\"area\")")
    p = r.props(e, {"radiance": "color"})
    if "radiance" not in p:
        raise r.fail(e, "an area light needs <color name=\"radiance\">")
    out = ET.Element("emitter", type="area")
    out.append(rgb("radiance", r.color(p["radiance"], 0)))
    return out


def mesh(r: Reader, e: ET.Element, albedo_one: bool) -> ET.Element:
    """Nori's OBJ mesh (src/obj.cpp) as Mitsuba's obj shape. Nori shades a mesh without `vn` normals with its
    face normals, where Mitsuba would compute vertex normals: such a mesh gets face_normals."""
    if e.get("type") != "obj":
        raise r.fail(e, "Nori's meshes are OBJ files (type=\"obj\")")
    p = r.props(e, {"filename": "string", "toWorld": "transform"}, objects=("bsdf", "emitter"))
    if not p.get("filename", ET.Element("x")).get("value"):
        raise r.fail(e, "a mesh needs <string name=\"filename\">")
    out = ET.Element("shape", type="obj")
    filename = p["filename"].get("value")
    ET.SubElement(out, "string", name="filename", value=filename)
    if obj_has_normals(filename, r.doc.path) is False:
        ET.SubElement(out, "boolean", name="face_normals", value="true")
    out.extend(r.transform(p.get("toWorld")))
    bsdfs, emitters = [c for c in e if c.tag == "bsdf"], [c for c in e if c.tag == "emitter"]
    for extra in (bsdfs[1:], emitters[1:]):
        if extra:
            raise r.fail(extra[0], f"a mesh has one <{extra[0].tag}>")
    out.append(bsdf(r, bsdfs[0] if bsdfs else None, albedo_one))
    if emitters:
        out.append(area_emitter(r, emitters[0]))
    return out


def light(r: Reader, e: ET.Element) -> tuple[str, ET.Element]:
    """A top-level Nori emitter as (its kind, Mitsuba's emitter): a point light (position, power in W:
    intensity power / 4 pi, as Nori's test-direct scenes mean it) or a distantdisk over the whole sphere
    (thetaA 180: a constant environment)."""
    kind = e.get("type")
    if kind == "point":
        p = r.props(e, {"position": "point", "power": "color", "energy": "color"})
        if "position" not in p or ("power" in p) == ("energy" in p):
            raise r.fail(e, "a point light needs <point name=\"position\"> and one <color name=\"power\">")
        power = r.color(p.get("power", p.get("energy")), 0)
        return "point", _point_light(r.triple(p["position"]), power)
    if kind == "distantdisk":
        p = r.props(e, {"radiance": "color", "thetaA": "float", "toWorld": "transform"})
        out = ET.Element("emitter", type="constant")
        out.append(rgb("radiance", r.color(p.get("radiance"), 1)))
        return "environment", out
    if kind == "area":
        raise r.fail(e, "an area light belongs inside the <mesh> that emits")
    raise r.fail(e, "of Nori's emitters only point, area and a full-sphere distantdisk have a counterpart")


def unmatched_light(r: Reader, e: ET.Element) -> str | None:
    """The note for a top-level emitter that only the file's own integrator would use and Mitsuba has no
    counterpart of (a distantdisk narrower than the whole sphere), or None."""
    if e.get("type") != "distantdisk":
        return None
    p = r.props(e, {"radiance": "color", "thetaA": "float", "toWorld": "transform"})
    if r.number(p.get("thetaA"), 0) >= 180:
        return None
    return (f"{r.doc.where(e)}: <emitter type=\"distantdisk\">: left out: narrower than thetaA = 180 it has no Mitsuba "
            "equivalent (at 180 it is a constant environment); no integrator of mcval's reads it")


def _point_light(position: list[float], power: list[float]) -> ET.Element:
    out = ET.Element("emitter", type="point")
    ET.SubElement(out, "point", name="position", value=triple_text(position))
    out.append(rgb("intensity", [w / (4 * math.pi) for w in power]))
    return out


def integrator_light(r: Reader, e: ET.Element) -> ET.Element:
    """Nori's simple integrator's own light (position, energy) as a point light."""
    p = r.props(e, {"position": "point", "energy": "color"})
    if set(p) != {"position", "energy"}:
        raise r.fail(e, "Nori's simple integrator needs <point name=\"position\"> and <color name=\"energy\">")
    return _point_light(r.triple(p["position"]), r.color(p["energy"], 0))
