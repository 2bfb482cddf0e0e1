"""Scene files rewritten by a physical transformation, so every scene gets each invariance for free.

Geometry: a step (scale, rotate, translate) appended AFTER the existing steps of every shape's and the
sensor's to_world (both our loader and Mitsuba's compose steps in document order), one added where a shape
has none; a perspective sensor's scale is conjugated, S C S^-1, as Mitsuba's perspective camera must be
rigid, while an orthographic one scales. Point-light positions and sphere centres are mapped by the same
matrix. Scaling also scales the sensor's clip distances (written explicitly: their defaults would not
scale; an orthographic sensor's span far_clip - near_clip instead) and point intensities by s^2, so that
1/r^2 leaves the image unchanged. Light and reflectance factors multiply every emitter's radiance or
intensity and every diffuse reflectance (defaults written out). Mesh paths are made absolute, so the
variant file can live anywhere.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from harness.engines.scene_paths import absolute_paths

#: Defaults of the properties a rewrite changes, in both loaders (mcval's: scene_loader.cpp; Mitsuba's plugins).
NEAR_CLIP, FAR_CLIP = 1e-2, 1e4
DEFAULT_REFLECTANCE = 0.5
DEFAULT_EMISSION = 1.0
LIGHTS = ("point", "constant", "area")


def _fmt(x: float) -> str:
    return repr(float(x))


def _numbers(node: ET.Element, attr: str = "value") -> np.ndarray:
    text = node.get(attr, "")
    if "$" in text:
        raise ValueError(f"<{node.tag} name=\"{node.get('name')}\"> holds a parameter ({text}): cannot rewrite it")
    return np.array([float(v) for v in text.replace(",", " ").split()])


def _prop(parent: ET.Element, name: str) -> ET.Element | None:
    return next((e for e in parent if e.get("name") == name), None)


def scale_matrix(s: float) -> np.ndarray:
    return np.diag([s, s, s, 1.0])


def rotation_matrix(axis, degrees: float) -> np.ndarray:
    """Rodrigues' rotation by `degrees` about the unit `axis`, right-handed, as <rotate> means it."""
    a = np.asarray(axis, float)
    x, y, z = a / np.linalg.norm(a)
    t = np.radians(degrees)
    c, s = np.cos(t), np.sin(t)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    m = np.eye(4)
    m[:3, :3] = c * np.eye(3) + s * k + (1 - c) * np.outer([x, y, z], [x, y, z])
    return m


def translation_matrix(v) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = v
    return m


def _step_element(kind: str, value) -> ET.Element:
    if kind == "scale":
        return ET.Element("scale", value=_fmt(value))
    if kind == "translate":
        return ET.Element("translate", value=", ".join(_fmt(v) for v in value))
    axis, angle = value
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    return ET.Element("rotate", x=_fmt(x), y=_fmt(y), z=_fmt(z), angle=_fmt(angle))


def step_matrix(kind: str, value) -> np.ndarray:
    return {"scale": scale_matrix, "translate": translation_matrix,
            "rotate": lambda v: rotation_matrix(*v)}[kind](value)


def _append_step(owner: ET.Element, step: ET.Element) -> None:
    """`step` after every step of the owner's to_world (a to_world made if it has none)."""
    transform = next((e for e in owner if e.tag == "transform" and e.get("name") == "to_world"), None)
    if transform is None:
        transform = ET.SubElement(owner, "transform", name="to_world")
    transform.append(step)


def _prepend_step(owner: ET.Element, step: ET.Element) -> None:
    transform = next(e for e in owner if e.tag == "transform" and e.get("name") == "to_world")
    transform.insert(0, step)


def _map_point(node: ET.Element, m: np.ndarray) -> None:
    if node.get("value") is not None:
        p = _numbers(node)
    else:
        p = np.array([float(node.get(a, "0")) for a in "xyz"])
        for a in "xyz":
            node.attrib.pop(a, None)
    q = m[:3, :3] @ p + m[:3, 3]
    node.set("value", ", ".join(_fmt(v) for v in q))


def _scale_value(node: ET.Element, factor: float) -> None:
    if node.tag not in ("rgb", "float", "spectrum", "integer") or node.get("value") is None:
        raise ValueError(f"cannot scale <{node.tag} name=\"{node.get('name')}\">: expected an <rgb> or <float> value")
    if node.tag == "integer":  # a length written as a whole number (focus_distance="10"): scaled, it is a float
        node.tag = "float"
    if node.tag == "spectrum" and ":" in node.get("value", ""):
        # Given per wavelength: each value scaled, which scales its RGB (linear but for clamping out of gamut).
        pairs = [entry.split(":") for entry in node.get("value").split(",")]
        if any(len(pair) != 2 for pair in pairs):
            raise ValueError(f"cannot scale <spectrum name=\"{node.get('name')}\">: expected wavelength:value pairs")
        node.set("value", ", ".join(f"{nm.strip()}:{_fmt(float(v) * factor)}" for nm, v in pairs))
        return
    v = _numbers(node) * factor
    if node.tag == "spectrum" and v.size != 1:
        raise ValueError(f"cannot scale a sampled <spectrum name=\"{node.get('name')}\">")
    node.set("value", ", ".join(_fmt(x) for x in v))


def _scale_property(owner: ET.Element, name: str, factor: float, default: float) -> None:
    node = _prop(owner, name)
    if node is None:
        node = ET.SubElement(owner, "float", name=name, value=_fmt(default))
    _scale_value(node, factor)


def _scale_orthographic_clips(sensor: ET.Element, s: float) -> None:
    """An orthographic camera may scale, so S C (the step appended) scales its view and moves its near plane
    with the world; its rays run far_clip - near_clip in world units, so that span is scaled, near_clip kept."""
    values = {}
    for name, default in (("near_clip", NEAR_CLIP), ("far_clip", FAR_CLIP)):
        node = _prop(sensor, name)
        if node is None:
            node = ET.SubElement(sensor, "float", name=name, value=_fmt(default))
        values[name] = node
    near, far = (float(_numbers(values[n])[0]) for n in ("near_clip", "far_clip"))
    values["far_clip"].tag = "float"
    values["far_clip"].set("value", _fmt(near + s * (far - near)))


def transform_scene(root: ET.Element, kind: str, value) -> None:
    """Apply the rigid or scaling step (kind "scale", "rotate" (axis, degrees) or "translate") to everything."""
    m = step_matrix(kind, value)
    s = float(value) if kind == "scale" else 1.0
    for sensor in root.iter("sensor"):
        _append_step(sensor, _step_element(kind, value))
        if kind == "scale" and sensor.get("type") == "orthographic":
            _scale_orthographic_clips(sensor, s)
        elif kind == "scale":
            # Mitsuba's perspective camera refuses a scaled to_world: S C S^-1 moves it as S does and stays rigid.
            _prepend_step(sensor, _step_element(kind, 1.0 / s))
            for name, default in (("near_clip", NEAR_CLIP), ("far_clip", FAR_CLIP), ("focus_distance", None)):
                if default is not None or _prop(sensor, name) is not None:
                    _scale_property(sensor, name, s, default)
    # The shapes that stand in the world: a shapegroup's members are placed by its instances, which move.
    for shape in [e for e in root.findall("shape") if e.get("type") != "shapegroup"]:
        if shape.get("type") == "sphere" and not any(e.tag == "transform" for e in shape):
            # Mitsuba's sphere is to_world * translate(center) * scale(radius): without a to_world, move those.
            centre = _prop(shape, "center")
            if centre is None:
                centre = ET.SubElement(shape, "point", name="center", value="0, 0, 0")
            _map_point(centre, m)
            if kind == "scale":
                _scale_property(shape, "radius", s, 1.0)
            continue
        _append_step(shape, _step_element(kind, value))
    for emitter in root.iter("emitter"):
        kind_of = emitter.get("type")
        if kind_of == "point":
            if any(e.tag == "transform" for e in emitter):
                _append_step(emitter, _step_element(kind, value))
            else:
                position = _prop(emitter, "position")
                if position is None:
                    position = ET.SubElement(emitter, "point", name="position", value="0, 0, 0")
                _map_point(position, m)
            if kind == "scale":
                _scale_property(emitter, "intensity", s * s, DEFAULT_EMISSION)
        elif kind_of not in ("constant", "area"):
            raise ValueError(f"cannot move <emitter type=\"{kind_of}\">: only {', '.join(LIGHTS)} are known")


def scale_lights(root: ET.Element, factor: float) -> None:
    """Every emitter's intensity (point) or radiance (constant, area) times `factor`."""
    for emitter in root.iter("emitter"):
        kind = emitter.get("type")
        if kind not in LIGHTS:
            raise ValueError(f"cannot scale <emitter type=\"{kind}\">: only {', '.join(LIGHTS)} are known")
        _scale_property(emitter, "intensity" if kind == "point" else "radiance", factor, DEFAULT_EMISSION)


def unscaled_bsdfs(root: ET.Element) -> list[str]:
    """The types of the scene's BSDFs whose reflectance scale_reflectance leaves as it is (all but diffuse and
    twosided): an image linear in the diffuse reflectance is not halved where they reflect light."""
    return sorted({b.get("type", "") for b in root.iter("bsdf")} - {"diffuse", "twosided"})


def scale_reflectance(root: ET.Element, factor: float) -> None:
    """Every diffuse reflectance times `factor`; a shape with no material gets the default one, scaled. Other
    BSDFs are left as they are (unscaled_bsdfs): an integrator that reads no material sees no change either way."""
    for shape in root.iter("shape"):
        if shape.get("type") in ("shapegroup", "instance"):  # their members carry the materials
            continue
        if not any(e.tag in ("bsdf", "ref") for e in shape):
            ET.SubElement(shape, "bsdf", type="diffuse")
    for bsdf in root.iter("bsdf"):
        kind = bsdf.get("type")
        if kind == "diffuse":
            _scale_property(bsdf, "reflectance", factor, DEFAULT_REFLECTANCE)


def rewrite(scene: Path, out: Path, kind: str, value) -> Path:
    """Write `scene` transformed by (kind, value) to `out`: kind is "scale", "rotate", "translate", "light"
    or "reflectance" (value the factor)."""
    tree = ET.parse(scene)
    root = tree.getroot()
    # Includes inlined and file names made absolute first: the rewrite must reach every shape, and the
    # variant is written elsewhere.
    absolute_paths(root, Path(scene))
    if kind in ("scale", "rotate", "translate"):
        transform_scene(root, kind, value)
    elif kind == "light":
        scale_lights(root, float(value))
    elif kind == "reflectance":
        scale_reflectance(root, float(value))
    else:
        raise ValueError(f"unknown rewrite {kind!r}")
    out.parent.mkdir(parents=True, exist_ok=True)
    tree.write(out, encoding="utf-8", xml_declaration=True)
    return out
