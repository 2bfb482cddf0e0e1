"""The suite's Mitsuba 3 elements written as Nori's, one function each (harness/engines/nori/to_nori.py):
what Nori reads with a default Mitsuba does not share (nearClip, the filter, the albedo) is written out."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Callable

from harness.engines.nori.baked_obj import world_obj
from harness.engines.nori.obj_mesh import read_obj
from harness.engines.nori.obj_shapes import OBJ_TEXT
from harness.engines.nori.ply_mesh import PlyError, read_ply
from harness.engines.nori.reader import obj_has_normals
from harness.engines.nori.transforms import mitsuba_to_nori as transform_to_nori
from harness.engines.nori.values import number_text, numbers, triple_text

Fail = Callable[[ET.Element, str], Exception]
#: Mitsuba's perspective defaults (src/sensors/perspective.cpp, src/films/hdrfilm.cpp).
MITSUBA_NEAR_CLIP, MITSUBA_FAR_CLIP, MITSUBA_FOCAL_LENGTH_MM = 1e-2, 1e4, 50.0
MITSUBA_FILM = {"width": 768, "height": 576}


def prop(e: ET.Element, name: str) -> ET.Element | None:
    return next((c for c in e if c.get("name") == name), None)


def number(e: ET.Element | None, default: float, fail: Fail) -> float:
    if e is None:
        return default
    values = numbers(e.get("value", "").removesuffix("mm"))
    if values is None or len(values) != 1:
        raise fail(e, "expected one finite number")
    return values[0]


def color(e: ET.Element | None, default: float, fail: Fail) -> list[float]:
    """An RGB value (<rgb> of one or three numbers, or a constant <spectrum>) as three numbers."""
    if e is None:
        return [default] * 3
    values = numbers(e.get("value", "")) if e.tag in ("rgb", "spectrum", "float") else None
    if values is None or len(values) not in (1, 3) or (e.tag != "rgb" and len(values) != 1):
        raise fail(e, "Nori's colours are RGB: give an <rgb> of one or three numbers (or a constant spectrum)")
    return values * 3 if len(values) == 1 else values


def color_element(name: str, values: list[float]) -> ET.Element:
    return ET.Element("color", name=name, value=triple_text(values))


def horizontal_fov(sensor: ET.Element, width: int, height: int, fail: Fail) -> float:
    """Mitsuba's field of view (fov along fov_axis, or focal_length along the diagonal, default 50 mm) as
    Nori's, which is along x."""
    fov_e = prop(sensor, "fov")
    if fov_e is not None:
        fov = number(fov_e, 0, fail)
        axis_e = prop(sensor, "fov_axis")
        axis = "x" if axis_e is None else axis_e.get("value", "")
        axis = {"smaller": "x" if width <= height else "y", "larger": "x" if width >= height else "y"}.get(axis, axis)
    else:
        focal = number(prop(sensor, "focal_length"), MITSUBA_FOCAL_LENGTH_MM, fail)
        fov, axis = math.degrees(2 * math.atan(math.hypot(36, 24) / (2 * focal))), "diagonal"
    scale = {"x": 1.0, "y": width / height, "diagonal": width / math.hypot(width, height)}.get(axis)
    if scale is None:
        raise fail(axis_e, "fov_axis must be x, y, diagonal, smaller or larger")
    if not 0 < fov < 180:
        raise fail(fov_e if fov_e is not None else sensor, f"the field of view must be between 0 and 180 degrees "
                                                           f"(got {fov:g})")
    return math.degrees(2 * math.atan(math.tan(math.radians(fov) / 2) * scale))


def rfilter(film: ET.Element, fail: Fail) -> ET.Element:
    """Mitsuba's filter (default gaussian, stddev 0.5, radius 4 stddev) as Nori's, radius written out."""
    e = next((c for c in film if c.tag == "rfilter"), None)
    kind = "gaussian" if e is None else e.get("type")
    out = ET.Element("rfilter", type=kind)
    if kind == "gaussian":
        stddev = number(None if e is None else prop(e, "stddev"), 0.5, fail)
        ET.SubElement(out, "float", name="radius", value=number_text(4 * stddev))
        ET.SubElement(out, "float", name="stddev", value=number_text(stddev))
    elif kind == "tent":
        ET.SubElement(out, "float", name="radius", value=number_text(number(prop(e, "radius"), 1.0, fail)))
    elif kind == "mitchell":
        ET.SubElement(out, "float", name="radius", value="2")
        for name in ("B", "C"):
            ET.SubElement(out, "float", name=name, value=number_text(number(prop(e, name), 1 / 3, fail)))
    elif kind != "box":
        raise fail(e, "Nori's filters are box, gaussian, tent and mitchell")
    return out


def camera(sensor: ET.Element, fail: Fail) -> tuple[ET.Element, int, int]:
    """Mitsuba's perspective sensor as Nori's camera, with its film's size."""
    if sensor.get("type") != "perspective":
        raise fail(sensor, "Nori's camera is perspective")
    film = next((c for c in sensor if c.tag == "film"), ET.Element("film", type="hdrfilm"))
    size = [number(prop(film, k), MITSUBA_FILM[k], fail) for k in ("width", "height")]
    if not all(v >= 1 and float(v).is_integer() for v in size):
        raise fail(film, f"the film's size must be whole numbers of pixels, at least 1 (got {size[0]:g} x {size[1]:g})")
    width, height = (int(v) for v in size)
    out = ET.Element("camera", type="perspective")
    transform = next((c for c in sensor if c.tag == "transform" and c.get("name") == "to_world"), None)
    if transform is not None:
        out.append(transform_to_nori(transform, fail))
    ET.SubElement(out, "float", name="fov", value=number_text(horizontal_fov(sensor, width, height, fail)))
    for nori_name, mitsuba_name, default in (("nearClip", "near_clip", MITSUBA_NEAR_CLIP),
                                             ("farClip", "far_clip", MITSUBA_FAR_CLIP)):
        value = number(prop(sensor, mitsuba_name), default, fail)
        ET.SubElement(out, "float", name=nori_name, value=number_text(value))
    ET.SubElement(out, "integer", name="width", value=str(width))
    ET.SubElement(out, "integer", name="height", value=str(height))
    out.append(rfilter(film, fail))
    return out, width, height


def reflectance(bsdf: ET.Element | None, fail: Fail) -> list[float]:
    """A diffuse BSDF's reflectance (Mitsuba's default 0.5, as Nori's albedo)."""
    if bsdf is None:
        return [0.5] * 3
    if bsdf.get("type") != "diffuse":
        raise fail(bsdf, "of Mitsuba's BSDFs only diffuse is written for Nori (mcval's integrators model no other)")
    return color(prop(bsdf, "reflectance"), 0.5, fail)


def mesh(shape: ET.Element, index: int, albedo: list[float], fail: Fail) -> tuple[ET.Element, dict[str, str]]:
    """A shape as Nori's OBJ mesh, and the OBJ files to write beside the scene (name -> text). An OBJ that Nori
    shades as Mitsuba does (its `vn` normals, or face normals under face_normals and no `vn`) is named as it is;
    other meshes are written again in world space with the normals Mitsuba shades them with (baked_obj.py),
    flat shapes as they are (obj_shapes.py)."""
    kind, files = shape.get("type"), {}
    face = prop(shape, "face_normals")
    face_normals = face is not None and face.get("value", "").strip().lower() == "true"
    if prop(shape, "flip_normals") is not None:
        raise fail(prop(shape, "flip_normals"), "Nori has no flip_normals")
    transform = _to_world(shape)
    written = None if transform is None else transform_to_nori(transform, fail)  # checks its steps too
    filename = prop(shape, "filename")
    source = Path("" if filename is None else filename.get("value", ""))
    if kind in OBJ_TEXT:
        name = f"{kind}_{index}.obj"
        files[name] = OBJ_TEXT[kind]
    elif kind == "obj" and obj_has_normals(str(source), source) is (not face_normals):
        name = str(source)  # Nori shades it as Mitsuba does: with its vn normals, or flat without any
    elif kind in ("obj", "ply"):
        name, written = f"{kind}_{index}.obj", None  # in world space: no toWorld
        try:
            files[name] = world_obj((read_obj if kind == "obj" else read_ply)(source), transform, face_normals)
        except (OSError, PlyError) as e:
            raise fail(shape, f"cannot be written as OBJ for Nori: {getattr(e, 'strerror', None) or e}") from None
    else:
        raise fail(shape, "Nori's meshes are OBJ files: of Mitsuba's shapes only obj, ply, rectangle and cube "
                          "are written for it")
    out = ET.Element("mesh", type="obj")
    ET.SubElement(out, "string", name="filename", value=name)
    if written is not None:
        out.append(written)
    bsdf = ET.SubElement(out, "bsdf", type="diffuse")
    bsdf.append(color_element("albedo", albedo))
    return out, files


def _to_world(e: ET.Element) -> ET.Element | None:
    return next((c for c in e if c.tag == "transform" and c.get("name") == "to_world"), None)


def point_position(emitter: ET.Element, fail: Fail) -> list[float]:
    """A point light's position: `position`, or a to_world that is one translation."""
    p = prop(emitter, "position")
    if p is not None:
        values = numbers(p.get("value", "")) if "value" in p.attrib else \
            numbers(" ".join(p.get(a, "0") for a in "xyz"))
        if values is None or len(values) != 3:
            raise fail(p, "expected a position of three finite numbers")
        return values
    steps = [c for c in emitter if c.tag == "transform" for c in c]
    if len(steps) == 1 and steps[0].tag == "translate":
        return [float(v) for v in transform_to_nori(next(c for c in emitter if c.tag == "transform"), fail)[0]
                .get("value").split(",")]
    if not steps:
        return [0.0, 0.0, 0.0]
    raise fail(emitter, "write the point light's place as position=\"x, y, z\" for Nori")


def area_radiance(shape: ET.Element, fail: Fail) -> list[float] | None:
    """The radiance of the shape's area emitter (Mitsuba's default 1), or None if it emits nothing."""
    emitter = next((c for c in shape if c.tag == "emitter"), None)
    if emitter is None:
        return None
    if emitter.get("type") != "area":
        raise fail(emitter, "an emitter inside a shape is an area light (type=\"area\")")
    return color(prop(emitter, "radiance"), 1, fail)
