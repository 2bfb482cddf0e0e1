"""A second, independent reading of the scenes that have a closed-form image: one plane (and at most one
sphere resting on it), point lights and a constant emitter, or one plane under one area light
(harness/closed_forms/lit_plane.py), seen through Mitsuba's perspective camera with a box filter.

Written apart from the C++ loader on purpose, so a mistake there cannot hide here.
"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np


class NotAnalytic(ValueError):
    """The scene has no closed form (more than one plane, a filter other than box, ...)."""


#: What reading a file that is no scene the closed forms know raises (broken XML, a property missing or malformed):
#: each reader turns it into NotAnalytic.
UNREADABLE = (ET.ParseError, AttributeError, KeyError, TypeError, ValueError, IndexError)


@dataclass(frozen=True)
class Sphere:
    """An exact sphere in world space."""

    center: np.ndarray
    radius: float
    reflectance: np.ndarray


@dataclass
class PlaneScene:
    """Everything the closed forms need, in world space."""

    origin: np.ndarray      # camera position
    to_world: np.ndarray    # 3x3 camera frame: columns left, up, forward
    tan_half_x: float
    width: int
    height: int
    near_clip: float
    plane: np.ndarray       # 4x4 rectangle to_world ([-1,1]^2 at z = 0, front +z)
    reflectance: np.ndarray
    lights: list[tuple[np.ndarray, np.ndarray]]  # (position, intensity W/sr)
    environment: np.ndarray
    far_clip: float = 1e4
    sphere: Sphere | None = None  # resting on the plane (checked by analytic_sphere)
    #: The emitting shapes (harness/closed_forms/area_lights.py), checked by lit_plane.check_lit.
    area_lights: tuple = ()
    #: Which surface the points handed to a closed form lie on ("floor" or "sphere"); set per call.
    surface: str = "floor"

    @property
    def kind(self) -> str:
        """"plane" (a lone plane), "sphere_floor" (a sphere resting on it) or "lit_plane" (a plane under an area
        light): what a closed form must cover."""
        if self.sphere is not None:
            return "sphere_floor"
        return "lit_plane" if self.area_lights else "plane"


def _numbers(text: str) -> np.ndarray:
    return np.array([float(x) for x in re.split(r"[,\s]+", text.strip()) if x])


def _triple(el: ET.Element, attr: str = "value", default: float = 0.0) -> np.ndarray:
    if el.get(attr) is not None:
        v = _numbers(el.get(attr))
        return np.repeat(v, 3) if v.size == 1 else v
    return np.array([float(el.get(a, default)) for a in "xyz"])


def _transform(el: ET.Element | None) -> np.ndarray:
    m = np.eye(4)
    if el is None:
        return m
    for step in el:
        t = np.eye(4)
        if step.tag == "translate":
            t[:3, 3] = _triple(step)
        elif step.tag == "scale":
            t[:3, :3] = np.diag(_triple(step, default=1.0))
        elif step.tag == "rotate":
            axis = _triple(step)
            axis = axis / np.linalg.norm(axis)
            a = np.radians(float(step.get("angle")))
            k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
            t[:3, :3] = np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k  # Rodrigues
        elif step.tag == "matrix":
            t = _numbers(step.get("value")).reshape(4, 4)
        elif step.tag == "lookat":
            o, target = _triple(step, "origin"), _triple(step, "target")
            up = _triple(step, "up") if step.get("up") else np.array([0.0, 1.0, 0.0])
            d = (target - o) / np.linalg.norm(target - o)
            left = np.cross(up, d)
            left /= np.linalg.norm(left)
            t[:3, :3] = np.stack([left, np.cross(d, left), d], axis=1)
            t[:3, 3] = o
        else:
            raise NotAnalytic(f"transform step <{step.tag}>")
        m = t @ m
    return m


def prop(el: ET.Element, tag: str, name: str) -> ET.Element | None:
    """el's child <tag name="name">, or None."""
    return next((c for c in el if c.tag == tag and c.get("name") == name), None)


def is_true(el: ET.Element, name: str) -> bool:
    """Whether el's <boolean name="name"> says true (absent: false)."""
    flag = prop(el, "boolean", name)
    return flag is not None and flag.get("value", "").strip().lower() == "true"


def color(el: ET.Element, name: str, default: float) -> np.ndarray:
    """The RGB (3,) of el's child named `name` (a gray `default` without one)."""
    c = next((c for c in el if c.get("name") == name), None)
    return np.full(3, default) if c is None else _triple(c)


def reflectance(shape: ET.Element, bsdfs: dict[str, ET.Element]) -> np.ndarray:
    """A shape's diffuse reflectance (its own <bsdf> or one it refers to; 0.5 without); NotAnalytic for another
    BSDF."""
    bsdf = shape.find("bsdf")
    if bsdf is None and shape.find("ref") is not None:
        bsdf = bsdfs[shape.find("ref").get("id")]
    if bsdf is not None and bsdf.get("type") != "diffuse":
        raise NotAnalytic(f"bsdf {bsdf.get('type')}: closed forms are for diffuse surfaces")
    return color(bsdf, "reflectance", 0.5) if bsdf is not None else np.full(3, 0.5)


def shape_to_world(shape: ET.Element) -> np.ndarray:
    """A shape's to_world as a 4x4 matrix, its steps composed in file order (the identity without one)."""
    return _transform(prop(shape, "transform", "to_world"))


def sphere_geometry(shape: ET.Element) -> tuple[np.ndarray, float]:
    """Mitsuba's sphere in world space, (centre, radius): center and radius, then to_world (a uniform
    scale, rotation and translation)."""
    m = _transform(prop(shape, "transform", "to_world"))
    scales = np.linalg.svd(m[:3, :3], compute_uv=False)
    if not np.allclose(scales, scales[0], rtol=1e-9):
        raise NotAnalytic("a sphere's to_world that is not a similarity (an ellipsoid)")
    center = prop(shape, "point", "center")
    radius = prop(shape, "float", "radius")
    c = _triple(center) if center is not None else np.zeros(3)
    r = float(radius.get("value")) if radius is not None else 1.0
    return m[:3, :3] @ c + m[:3, 3], abs(r) * float(scales[0])


def _sphere(shape: ET.Element, bsdfs: dict[str, ET.Element]) -> Sphere:
    return Sphere(*sphere_geometry(shape), reflectance(shape, bsdfs))


def _tiled_plane(planes: list[ET.Element], bsdfs: dict[str, ET.Element]) -> tuple[np.ndarray, np.ndarray]:
    """One rectangle's to_world and reflectance for rectangles that tile one: coplanar, edges parallel,
    the same reflectance, no overlap and no gap (a floor may be tiled so that the part the camera sees
    has small float32 vertices). Raises NotAnalytic otherwise."""
    mats = [_transform(prop(s, "transform", "to_world")) for s in planes]
    rho = reflectance(planes[0], bsdfs)
    if len(mats) == 1:
        return mats[0], rho
    m0 = mats[0]
    u, v = m0[:3, 0] / np.linalg.norm(m0[:3, 0]), m0[:3, 1] / np.linalg.norm(m0[:3, 1])
    n = np.cross(u, v)
    boxes = []
    for m, shape in zip(mats, planes):
        if not np.allclose(reflectance(shape, bsdfs), rho):
            raise NotAnalytic("floor tiles of different reflectance")
        a, b = m[:3, 0], m[:3, 1]
        if not (np.allclose(np.cross(a, b) / np.linalg.norm(np.cross(a, b)), n, atol=1e-9)
                and abs(np.dot(m[:3, 3] - m0[:3, 3], n)) <= 1e-9 * np.linalg.norm(m[:3, 3] - m0[:3, 3] + 1e-300)
                and abs(np.dot(a, v)) <= 1e-9 * np.linalg.norm(a) and abs(np.dot(b, u)) <= 1e-9 * np.linalg.norm(b)):
            raise NotAnalytic("floor tiles that are not coplanar with parallel edges")
        c = m[:3, 3] - m0[:3, 3]
        hu, hv = abs(np.dot(a, u)), abs(np.dot(b, v))
        boxes.append((np.dot(c, u) - hu, np.dot(c, u) + hu, np.dot(c, v) - hv, np.dot(c, v) + hv))
    boxes = np.array(boxes)
    lo_u, hi_u, lo_v, hi_v = boxes[:, 0].min(), boxes[:, 1].max(), boxes[:, 2].min(), boxes[:, 3].max()
    area = (hi_u - lo_u) * (hi_v - lo_v)
    areas = (boxes[:, 1] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 2])
    overlap = sum(max(0.0, min(p[1], q[1]) - max(p[0], q[0])) * max(0.0, min(p[3], q[3]) - max(p[2], q[2]))
                  for i, p in enumerate(boxes) for q in boxes[i + 1:])
    if overlap > 1e-9 * area or abs(areas.sum() - area) > 1e-9 * area:
        raise NotAnalytic("floor tiles that overlap or leave a gap")
    whole = np.eye(4)
    whole[:3, 0], whole[:3, 1], whole[:3, 2] = u * (hi_u - lo_u) / 2, v * (hi_v - lo_v) / 2, n
    whole[:3, 3] = m0[:3, 3] + u * (hi_u + lo_u) / 2 + v * (hi_v + lo_v) / 2
    return whole, rho


def check_framing(sensor: ET.Element, film: ET.Element) -> None:
    """NotAnalytic unless the film is rendered whole through a centred pinhole: a crop window, a principal point
    offset or a sampled border would give another image than the closed forms' (or one of another size)."""
    framing = [e.get("name") for e in (*film, *sensor) if e.get("name", "").startswith(("crop_", "principal_point"))
               or (e.get("name") == "sample_border" and e.get("value", "").strip().lower() == "true")]
    if framing:
        raise NotAnalytic(f"closed forms cover the whole film through a centred pinhole, not {framing[0]}")


def load_plane_scene(path: str | Path, params: dict[str, str] | None = None) -> PlaneScene:
    """Reads a one-plane scene (the plane possibly tiled), or one plane and one sphere; raises NotAnalytic
    for anything else, a file that is no scene file included (its case then fails where it renders, with
    the renderer's own message). That the sphere rests on the plane is checked where its closed forms are,
    analytic_sphere."""
    try:
        return _read_plane_scene(path, params)
    except NotAnalytic:
        raise
    except UNREADABLE as e:
        raise NotAnalytic(f"not a scene file the closed forms read ({type(e).__name__}: {e})") from e


def resolved_root(path: str | Path, params: dict[str, str] | None) -> ET.Element:
    """The scene file's root with its $name parameters (in attribute values) replaced: `params` first, then the
    file's <default>s."""
    return resolve(ET.fromstring(Path(path).read_text()), params)


def resolve(root: ET.Element, params: dict[str, str] | None) -> ET.Element:
    """`root` with its $name parameters replaced in place, as resolved_root."""
    values = {d.get("name"): d.get("value") for d in root.iter("default")}
    values.update({k: str(v) for k, v in (params or {}).items()})
    for el in root.iter():
        for key, value in el.attrib.items():
            el.set(key, re.sub(r"\$(\w+)", lambda m: values[m.group(1)], value))
    return root


def _read_plane_scene(path: str | Path, params: dict[str, str] | None) -> PlaneScene:
    root = resolved_root(path, params)
    sensor = root.find("sensor")
    film = sensor.find("film") if sensor is not None else None
    if film is None:
        raise NotAnalytic("no <sensor> with a <film>")
    if sensor.get("type") != "perspective":
        raise NotAnalytic(f"the closed forms see through the perspective sensor, not {sensor.get('type')!r}")
    rfilter = film.find("rfilter")
    if rfilter is None or rfilter.get("type") != "box":
        raise NotAnalytic("closed forms are integrated over pixels with a box filter")
    check_framing(sensor, film)
    if (prop(sensor, "string", "fov_axis") is not None) and prop(sensor, "string", "fov_axis").get("value") != "x":
        raise NotAnalytic("fov_axis other than x")
    emitting = [s for s in root.findall("shape") if s.find("emitter") is not None]
    shapes = [s for s in root.findall("shape") if s.find("emitter") is None]
    planes = [s for s in shapes if s.get("type") == "rectangle"]
    spheres = [s for s in shapes if s.get("type") == "sphere"]
    if not planes or len(spheres) > 1 or len(shapes) != len(planes) + len(spheres):
        raise NotAnalytic("the scene must be one rectangle (or rectangles tiling one), with at most one sphere")
    if emitting and root.findall("emitter"):
        raise NotAnalytic("area lights beside other emitters")
    bsdfs = {b.get("id"): b for b in root.findall("bsdf")}
    plane, rho = _tiled_plane(planes, bsdfs)
    far = prop(sensor, "float", "far_clip")
    cam = _transform(prop(sensor, "transform", "to_world"))
    near = prop(sensor, "float", "near_clip")
    lights, env = [], np.ones(3)
    for e in root.findall("emitter"):
        if e.get("type") == "point":
            lights.append((_triple(prop(e, "point", "position")), color(e, "intensity", 1.0)))
        elif e.get("type") == "constant":
            env = color(e, "radiance", 1.0)
    scene = PlaneScene(
        origin=cam[:3, 3], to_world=cam[:3, :3] / np.linalg.norm(cam[:3, :3], axis=0),
        tan_half_x=float(np.tan(np.radians(float(prop(sensor, "float", "fov").get("value"))) / 2)),
        width=int(prop(film, "integer", "width").get("value")),
        height=int(prop(film, "integer", "height").get("value")),
        near_clip=float(near.get("value")) if near is not None else 1e-2,
        plane=plane, reflectance=rho, lights=lights, environment=env,
        far_clip=float(far.get("value")) if far is not None else 1e4,
        sphere=_sphere(spheres[0], bsdfs) if spheres else None)
    if emitting:
        from harness.closed_forms import lit_plane  # it reads PlaneScene: imported here, not at the top

        for shape in emitting:
            if shape.find("emitter").get("type") != "area":
                raise NotAnalytic(f"a shape's {shape.find('emitter').get('type')} emitter")
        scene.area_lights = tuple(lit_plane.area_light(s, color(s.find("emitter"), "radiance", 1.0)) for s in emitting)
        lit_plane.check_lit(scene)
    return scene
