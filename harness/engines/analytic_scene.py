"""A second, independent reading of the scenes that have a closed-form image: one plane (and at most one
sphere resting on it), point lights and a constant emitter, seen through Mitsuba's perspective camera with a
box filter.

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
    #: Which surface the points handed to a closed form lie on ("floor" or "sphere"); set per call.
    surface: str = "floor"

    @property
    def kind(self) -> str:
        """"plane" (a lone plane) or "sphere_floor" (a sphere resting on it): what a closed form must cover."""
        return "plane" if self.sphere is None else "sphere_floor"


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


def _prop(el: ET.Element, tag: str, name: str) -> ET.Element | None:
    return next((c for c in el if c.tag == tag and c.get("name") == name), None)


def _color(el: ET.Element, name: str, default: float) -> np.ndarray:
    c = next((c for c in el if c.get("name") == name), None)
    return np.full(3, default) if c is None else _triple(c)


def _reflectance(shape: ET.Element, bsdfs: dict[str, ET.Element]) -> np.ndarray:
    bsdf = shape.find("bsdf")
    if bsdf is None and shape.find("ref") is not None:
        bsdf = bsdfs[shape.find("ref").get("id")]
    if bsdf is not None and bsdf.get("type") != "diffuse":
        raise NotAnalytic(f"bsdf {bsdf.get('type')}: closed forms are for diffuse surfaces")
    return _color(bsdf, "reflectance", 0.5) if bsdf is not None else np.full(3, 0.5)


def _sphere(shape: ET.Element, bsdfs: dict[str, ET.Element]) -> Sphere:
    """Mitsuba's sphere: center and radius, then to_world (a uniform scale, rotation and translation)."""
    m = _transform(_prop(shape, "transform", "to_world"))
    scales = np.linalg.svd(m[:3, :3], compute_uv=False)
    if not np.allclose(scales, scales[0], rtol=1e-9):
        raise NotAnalytic("a sphere's to_world that is not a similarity (an ellipsoid)")
    center = _prop(shape, "point", "center")
    radius = _prop(shape, "float", "radius")
    c = _triple(center) if center is not None else np.zeros(3)
    r = float(radius.get("value")) if radius is not None else 1.0
    return Sphere(m[:3, :3] @ c + m[:3, 3], abs(r) * float(scales[0]), _reflectance(shape, bsdfs))


def load_plane_scene(path: str | Path, params: dict[str, str] | None = None) -> PlaneScene:
    """Reads a one-plane scene, or one plane and one sphere; raises NotAnalytic for anything else (that the
    sphere rests on the plane is checked where its closed forms are, analytic_sphere)."""
    root = ET.fromstring(Path(path).read_text())
    values = {d.get("name"): d.get("value") for d in root.iter("default")}
    values.update({k: str(v) for k, v in (params or {}).items()})
    for el in root.iter():  # $name parameters, in attribute values only
        for key, value in el.attrib.items():
            el.set(key, re.sub(r"\$(\w+)", lambda m: values[m.group(1)], value))
    sensor = root.find("sensor")
    film = sensor.find("film")
    rfilter = film.find("rfilter")
    if rfilter is None or rfilter.get("type") != "box":
        raise NotAnalytic("closed forms are integrated over pixels with a box filter")
    if (_prop(sensor, "string", "fov_axis") is not None) and _prop(sensor, "string", "fov_axis").get("value") != "x":
        raise NotAnalytic("fov_axis other than x")
    shapes = root.findall("shape")
    planes = [s for s in shapes if s.get("type") == "rectangle"]
    spheres = [s for s in shapes if s.get("type") == "sphere"]
    if len(planes) != 1 or len(spheres) > 1 or len(shapes) != len(planes) + len(spheres):
        raise NotAnalytic("the scene must be a single rectangle, with at most one sphere")
    if any(s.find("emitter") is not None for s in shapes):
        raise NotAnalytic("an emitting shape")
    bsdfs = {b.get("id"): b for b in root.findall("bsdf")}
    shape = planes[0]
    far = _prop(sensor, "float", "far_clip")
    cam = _transform(_prop(sensor, "transform", "to_world"))
    near = _prop(sensor, "float", "near_clip")
    lights, env = [], np.ones(3)
    for e in root.findall("emitter"):
        if e.get("type") == "point":
            lights.append((_triple(_prop(e, "point", "position")), _color(e, "intensity", 1.0)))
        elif e.get("type") == "constant":
            env = _color(e, "radiance", 1.0)
    return PlaneScene(
        origin=cam[:3, 3], to_world=cam[:3, :3] / np.linalg.norm(cam[:3, :3], axis=0),
        tan_half_x=float(np.tan(np.radians(float(_prop(sensor, "float", "fov").get("value"))) / 2)),
        width=int(_prop(film, "integer", "width").get("value")),
        height=int(_prop(film, "integer", "height").get("value")),
        near_clip=float(near.get("value")) if near is not None else 1e-2,
        plane=_transform(_prop(shape, "transform", "to_world")),
        reflectance=_reflectance(shape, bsdfs), lights=lights, environment=env,
        far_clip=float(far.get("value")) if far is not None else 1e4,
        sphere=_sphere(spheres[0], bsdfs) if spheres else None)
