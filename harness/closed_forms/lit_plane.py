"""A plane lit by one area light (a rectangle, a disk or a sphere of constant radiance): its exact image under
direct illumination, L = rho / pi * E at every floor point (harness/closed_forms/area_lights.py gives E).

The closed forms hold where nothing but the light lights the floor and nothing hides either from the other, so
a scene is refused (NotAnalytic) unless: it has one area light and no other emitter and no sphere on the floor;
the light lies wholly above the floor (above every floor point's horizon); a disk is parallel to the floor and
faces it; and the camera can see no part of the light, nor can the light hide the floor from it (the light is
higher above the floor than the camera, and every camera ray goes down).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from harness.closed_forms.area_lights import AreaLight, DiskLight, PolygonLight, SphereLight, irradiance, lowest_height
from harness.closed_forms.plane_scene import NotAnalytic, PlaneScene, is_true, shape_to_world, sphere_geometry

#: The largest |cos| between a disk light's normal and the floor's plane for it to count as parallel.
PARALLEL_TOLERANCE = 1e-9


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def area_light(shape: ET.Element, radiance: np.ndarray) -> AreaLight:
    """The light of an emitting <shape> (Mitsuba's rectangle [-1,1]^2 and disk of radius 1 at z = 0 facing +z,
    and sphere), in world space; NotAnalytic for any other shape."""
    kind = shape.get("type")
    if kind == "sphere":
        if is_true(shape, "flip_normals"):
            raise NotAnalytic("a sphere light with flip_normals (it emits inwards)")
        center, radius = sphere_geometry(shape)
        return SphereLight(center, radius, radiance)
    if kind not in ("rectangle", "disk"):
        raise NotAnalytic(f"an emitting {kind}: the closed forms know rectangle, disk and sphere lights")
    m = shape_to_world(shape)
    normal = _unit(np.linalg.inv(m[:3, :3]).T @ np.array([0.0, 0.0, 1.0]))  # a normal goes by the inverse transpose
    normal = -normal if is_true(shape, "flip_normals") else normal
    if kind == "disk":
        scales = np.linalg.norm(m[:3, :2], axis=0)
        if abs(m[:3, 0] @ m[:3, 1]) > 1e-9 * scales.prod() or not np.isclose(scales[0], scales[1], rtol=1e-9):
            raise NotAnalytic("a disk light whose to_world makes it an ellipse")
        return DiskLight(m[:3, 3], normal, float(scales[0]), radiance)
    corners = np.array([m[:3, :3] @ np.array([x, y, 0.0]) + m[:3, 3] for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    if np.cross(corners[1] - corners[0], corners[2] - corners[0]) @ normal < 0:
        corners = corners[::-1]  # counter-clockwise about the emitting side
    return PolygonLight(corners, normal, radiance)


def floor_up(scene: PlaneScene) -> tuple[np.ndarray, np.ndarray]:
    """The floor's unit normal (its front side) and a point on it."""
    return _unit(np.linalg.inv(scene.plane[:3, :3]).T @ np.array([0.0, 0.0, 1.0])), scene.plane[:3, 3]


def _corner_rays(scene: PlaneScene) -> np.ndarray:
    """The world directions (4, 3) of the film's corner rays (every camera ray lies between them)."""
    tx = scene.tan_half_x
    ty = tx * scene.height / scene.width
    local = np.array([[x * tx, y * ty, 1.0] for x in (-1, 1) for y in (-1, 1)])
    return local @ scene.to_world.T


def check_lit(scene: PlaneScene) -> None:
    """NotAnalytic unless the lit plane's closed form holds (the module's conditions)."""
    if len(scene.area_lights) != 1:
        raise NotAnalytic(f"{len(scene.area_lights)} area lights: the closed form covers one (two may shadow each other)")
    if scene.sphere is not None:
        raise NotAnalytic("an area light over a floor with a sphere on it")
    up, origin = floor_up(scene)
    light = scene.area_lights[0]
    low = lowest_height(light, origin, up)
    if low <= 0:
        raise NotAnalytic("an area light that reaches below the floor's horizon")
    if isinstance(light, DiskLight) and (light.normal @ up > -1 + PARALLEL_TOLERANCE):
        raise NotAnalytic("a disk light that is not parallel to the floor, facing it")
    camera = float((scene.origin - origin) @ up)
    if not 0 < camera < low or np.any(_corner_rays(scene) @ up >= 0):
        raise NotAnalytic("the camera could see the area light, or the light hide the floor: the light must be "
                          "higher above the floor than the camera, and every camera ray go down")


def radiance(scene: PlaneScene, p: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """rho / pi * E (..., 3) at floor points p (..., 3) with the floor's unit normal."""
    return irradiance(scene.area_lights, p, normal) * (scene.reflectance / np.pi)


__all__ = ["PARALLEL_TOLERANCE", "area_light", "check_lit", "floor_up", "radiance"]
