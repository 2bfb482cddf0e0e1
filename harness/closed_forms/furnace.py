"""A furnace: the camera inside a closed sphere whose inside is diffuse of reflectance a and emits radiance Le.

Every camera ray meets the sphere's inside, and every ray leaving a point of it meets the inside again, where the
same radiance arrives from all directions: the image is one value, the sum of the emission reflected k times,
Le a^k, over the bounces the integrator follows.
- direct: Le (1 + a): the emission seen, and the emission reflected once.
- path with `max_depth` d (vertices, as Mitsuba counts them: 1 sees emitters only): Le (1 + a + ... + a^(d-1));
  without a limit (-1), Le / (1 - a). Russian roulette changes the estimator's noise, not its mean.

A scene is refused (NotAnalytic) unless its only shape is a sphere with flip_normals (its inside faces in),
diffuse (or with no BSDF: an emitter's shape is then black, as in Mitsuba), carrying an area emitter; there is no
other emitter; emitters are not hidden; and a perspective camera sits inside, farther from the wall than its
near clip reaches and with the whole sphere nearer than its far clip.
"""
from __future__ import annotations

import copy
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from harness.closed_forms.plane_scene import (UNREADABLE, NotAnalytic, check_framing, color, is_true, prop,
                                              reflectance, resolve, resolved_root, shape_to_world, sphere_geometry)


@dataclass(frozen=True)
class Furnace:
    """What the furnace's closed forms need."""

    width: int
    height: int
    albedo: np.ndarray      # the inside's diffuse reflectance (3,)
    radiance: np.ndarray    # the inside's emitted radiance (3,)
    #: The file's <integrator>: its type and its integer parameters (max_depth), as written.
    integrator: str
    integer_parameters: dict[str, int]

    @property
    def kind(self) -> str:
        return "furnace"


def _camera_fits(sensor, center: np.ndarray, radius: float, width: int, height: int) -> None:
    """NotAnalytic unless every camera ray's first hit on the sphere lies between the clip planes."""
    if sensor.get("type") != "perspective":
        raise NotAnalytic(f"a furnace is seen through the perspective sensor, not {sensor.get('type')!r}")
    axis = prop(sensor, "string", "fov_axis")
    if axis is not None and axis.get("value") != "x":
        raise NotAnalytic("fov_axis other than x")
    origin = shape_to_world(sensor)[:3, 3]
    near, far, fov = (prop(sensor, "float", n) for n in ("near_clip", "far_clip", "fov"))
    near = float(near.get("value")) if near is not None else 1e-2
    far = float(far.get("value")) if far is not None else 1e4
    if fov is None:
        raise NotAnalytic("a perspective camera without fov")
    tan_x = np.tan(np.radians(float(fov.get("value"))) / 2)
    tan_y = tan_x * height / width
    # A hit's depth is its distance times the cosine to the camera's axis, least at the film's corners.
    gap = radius - float(np.linalg.norm(origin - center))
    if gap * (1 + tan_x ** 2 + tan_y ** 2) ** -0.5 <= near or 2 * radius >= far:
        raise NotAnalytic("the camera must sit inside the sphere, its near clip short of the wall and its far "
                          "clip beyond the whole sphere")


def load_furnace(path: str | Path, params: dict[str, str] | None = None) -> Furnace:
    """Reads a furnace (the module's conditions); NotAnalytic for anything else, a broken file included."""
    try:
        return _read(resolved_root(path, params))
    except NotAnalytic:
        raise
    except UNREADABLE as e:
        raise NotAnalytic(f"not a furnace the closed forms read ({type(e).__name__}: {e})") from e


def is_furnace(root: ET.Element) -> bool:
    """Whether a scene's root (its $name parameters at their defaults) is a furnace."""
    try:
        _read(resolve(copy.deepcopy(root), None))
    except (NotAnalytic, *UNREADABLE):
        return False
    return True


def _read(root: ET.Element) -> Furnace:
    shapes = [e for e in root if e.tag == "shape"]
    if len(shapes) != 1 or shapes[0].get("type") != "sphere" or not is_true(shapes[0], "flip_normals"):
        raise NotAnalytic("a furnace is one sphere with flip_normals, and no other shape")
    (sphere,) = shapes
    emitter = sphere.find("emitter")
    if emitter is None or emitter.get("type") != "area" or any(True for e in root if e.tag == "emitter"):
        raise NotAnalytic("a furnace's only light is the area emitter on its sphere")
    own = next((e for e in root if e.tag == "integrator"), None)
    if own is not None and is_true(own, "hide_emitters"):
        raise NotAnalytic("hidden emitters: a camera ray then passes through the furnace's wall")
    sensor = root.find("sensor")
    film = sensor.find("film") if sensor is not None else None
    if film is None:
        raise NotAnalytic("no <sensor> with a <film>")
    check_framing(sensor, film)
    size = {n: prop(film, "integer", n) for n in ("width", "height")}
    width, height = (int(size[n].get("value")) if size[n] is not None else d for n, d in (("width", 768),
                                                                                         ("height", 576)))
    center, radius = sphere_geometry(sphere)
    _camera_fits(sensor, center, radius, width, height)
    bsdfs = {b.get("id"): b for b in root if b.tag == "bsdf"}
    has_bsdf = sphere.find("bsdf") is not None or sphere.find("ref") is not None
    albedo = reflectance(sphere, bsdfs) if has_bsdf else np.zeros(3)
    integers = {e.get("name"): int(e.get("value")) for e in (own if own is not None else ()) if e.tag == "integer"}
    return Furnace(width, height, albedo, color(emitter, "radiance", 1.0),
                   own.get("type", "") if own is not None else "", integers)


def direct_radiance(f: Furnace) -> np.ndarray:
    """Le (1 + a)."""
    return f.radiance * (1 + f.albedo)


def path_radiance(f: Furnace) -> np.ndarray:
    """Le (1 + a + ... + a^(d-1)) for the file's max_depth d (path's own <integrator>; Mitsuba's -1 otherwise),
    Le / (1 - a) without a limit; NotAnalytic where that sum diverges (a reflectance of 1 or more)."""
    depth = f.integer_parameters.get("max_depth", -1) if f.integrator == "path" else -1
    if depth < 0:
        if np.any(f.albedo >= 1):
            raise NotAnalytic("a furnace of reflectance 1 or more reflects without end")
        return f.radiance / (1 - f.albedo)
    return f.radiance * sum(f.albedo ** k for k in range(depth))


__all__ = ["Furnace", "direct_radiance", "is_furnace", "load_furnace", "path_radiance"]
