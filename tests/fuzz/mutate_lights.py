"""Seeded mutations of what the emitter and BSDF models read: an emitter's radiance, intensity or irradiance
(0, negative, huge, non-finite, malformed), a spot's cutoff_angle and beam_width, a directional's direction,
`direct`'s emitter_samples, bsdf_samples, shading_samples and hide_emitters, area emitters put inside shapes
(one, two, of the wrong type), delta and environment emitters added, and twosided BSDFs nested, emptied,
overfilled or made to refer to themselves. Given the same `random.Random`, a mutation is the same every time.
"""
from __future__ import annotations

import random
import re

#: Emitted values: zero, negative, huge (past kMaxEmission and float32), tiny, non-finite, malformed, per channel.
EMISSION = ["0", "-0", "-1", "1e-45", "1e15", "1.1e15", "1e30", "3.4e38", "1e39", "nan", "NaN", "inf", "-inf",
            "0, 0, 0", "1, -1, 1", "nan, 1, 1", "1, inf, 1", "1e15, 1e15, 1e15", "", "abc", "1 2", "1, 2", "$missing"]
#: Spot angles in degrees: the loader's range is [1e-3, 180], beam_width within cutoff_angle.
ANGLES = ["0", "-0", "-1", "1e-4", "1e-3", "0.001", "1", "19.99", "20", "45", "89.9", "90", "179.9", "180", "180.1",
          "360", "1e30", "nan", "inf", "-inf", ""]
#: Directions of a directional light: zero, tiny, huge, non-finite, too few numbers.
DIRECTIONS = ["0, 0, 0", "0, -1, 0", "1e-30, 0, 0", "1e-45, 0, 0", "1e39, 0, 0", "3e38, 3e38, 3e38", "nan, 0, 1",
              "0, inf, 0", "1, 2", "", "abc"]
#: Sample counts of `direct`: the loader's range is [0, 1024] each, at least one in all.
COUNTS = ["0", "-1", "1", "2", "1023", "1024", "1025", "2147483647", "-2147483648", "4294967296", "1e9", "1.5",
          "nan", "", "abc"]
BOOLEANS = ["true", "false", "True", "1", "0", "yes", "", "maybe"]
DIRECT_PROPERTIES = ["emitter_samples", "bsdf_samples", "shading_samples"]
#: Emitters added at the top level (and the same, wrong, inside a shape).
TOP_EMITTERS = ['<emitter type="spot"/>', '<emitter type="directional"/>', '<emitter type="constant"/>',
                '<emitter type="point"><point name="position" value="0, 2, 0"/></emitter>',
                '<emitter type="spot"><point name="position" value="0, 2, 0"/></emitter>',
                '<emitter type="spot"><float name="cutoff_angle" value="10"/><float name="beam_width" value="15"/>'
                '</emitter>',
                '<emitter type="directional"><vector name="direction" value="0, -1, 0"/>'
                '<transform name="to_world"><rotate x="1" angle="30"/></transform></emitter>',
                '<emitter type="directional"><transform name="to_world"><scale value="0"/></transform></emitter>',
                '<emitter type="spot"><transform name="to_world"><scale value="0"/></transform></emitter>',
                '<emitter type="area"><rgb name="radiance" value="1"/></emitter>', '<emitter type="envmap"/>',
                '<emitter type="projector"/>', '<emitter type="spot"><bsdf type="diffuse"/></emitter>']
#: What is put inside a shape: area emitters good and bad, and emitters a shape may not hold.
SHAPE_EMITTERS = ['<emitter type="area"/>', '<emitter type="area"><rgb name="radiance" value="1e15"/></emitter>',
                  '<emitter type="area"><rgb name="radiance" value="0"/></emitter>',
                  '<emitter type="area"><rgb name="radiance" value="-1"/></emitter>',
                  '<emitter type="area"><rgb name="radiance" value="nan"/></emitter>',
                  '<emitter type="area"><float name="radiance" value="2"/></emitter>',
                  '<emitter type="area"><rgb name="intensity" value="1"/></emitter>',
                  '<emitter type="area"><emitter type="area"/></emitter>',
                  '<emitter type="point"/>', '<emitter type="constant"/>', '<emitter type="spot"/>']
#: Twosided BSDFs, odd ones: empty, three sides, a non-bsdf inside, a diffuse reflectance out of range.
TWOSIDED = ['<bsdf type="twosided"/>', '<bsdf type="twosided"><bsdf type="diffuse"/><bsdf type="diffuse"/>'
            '<bsdf type="diffuse"/></bsdf>', '<bsdf type="twosided"><rgb name="reflectance" value="0.5"/></bsdf>',
            '<bsdf type="twosided"><emitter type="area"/></bsdf>', '<bsdf type="twosided"><bsdf type="conductor"/></bsdf>',
            '<bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="1.5"/></bsdf></bsdf>',
            '<bsdf type="twosided"><boolean name="allow_transmission" value="true"/><bsdf type="diffuse"/></bsdf>',
            '<bsdf type="twosided" id="self"><ref id="self"/></bsdf>']
#: How deep a twosided wrapper nests: within, at and past the loader's limit, and far past it.
DEPTHS = (1, 2, 3, 99, 100, 101, 1000)

EMITTED_RE = re.compile(rb'(name="(?:radiance|intensity|irradiance)"\s+value=")([^"]*)(")')
ANGLE_RE = re.compile(rb'(name="(?:cutoff_angle|beam_width)"\s+value=")([^"]*)(")')
DIRECTION_RE = re.compile(rb'(name="direction"\s+value=")([^"]*)(")')
COUNT_RE = re.compile(rb'(name="(?:emitter_samples|bsdf_samples|shading_samples)"\s+value=")([^"]*)(")')
HIDE_RE = re.compile(rb'(name="hide_emitters"\s+value=")([^"]*)(")')
SHAPE_OPEN_RE = re.compile(rb"<shape\b[^>]*[^/]>")
INTEGRATOR_RE = re.compile(rb"<integrator\b[^>]*?(/?)>")
SCENE_OPEN_RE = re.compile(rb"<scene\b[^>]*>")
BSDF_RE = re.compile(rb'<bsdf type="diffuse"[^>]*/>|<bsdf type="diffuse"[^>]*>.*?</bsdf>', re.S)


def _set_value(rng: random.Random, xml: bytes, pattern: re.Pattern, values: list[str]) -> bytes | None:
    """One value that `pattern` finds becomes another of `values`; None if there is none."""
    found = list(pattern.finditer(xml))
    if not found:
        return None
    m = rng.choice(found)
    new = rng.choice([v for v in values if v.encode() != m.group(2)])
    return xml[: m.start(2)] + new.encode() + xml[m.end(2):]


def _insert_after(xml: bytes, at: int, snippet: str | bytes) -> bytes:
    return xml[:at] + (snippet.encode() if isinstance(snippet, str) else snippet) + xml[at:]


def emitted_value(rng: random.Random, xml: bytes) -> bytes | None:
    return _set_value(rng, xml, EMITTED_RE, EMISSION)


def spot_angle(rng: random.Random, xml: bytes) -> bytes | None:
    """A spot's angle, or both (beam_width past cutoff_angle, equal, or zero)."""
    if rng.random() < 0.3:
        spot = rng.choice(['<float name="cutoff_angle" value="{}"/>', '<float name="beam_width" value="{}"/>'])
        return _add_to_emitter(rng, xml, b"spot", spot.format(rng.choice(ANGLES)))
    return _set_value(rng, xml, ANGLE_RE, ANGLES)


def direction(rng: random.Random, xml: bytes) -> bytes | None:
    return _set_value(rng, xml, DIRECTION_RE, DIRECTIONS)


def _add_to_emitter(rng: random.Random, xml: bytes, kind: bytes, snippet: str) -> bytes | None:
    opens = list(re.finditer(rb'<emitter type="' + kind + rb'"[^>]*(?<!/)>', xml))
    return _insert_after(xml, rng.choice(opens).end(), snippet) if opens else None


def direct_parameter(rng: random.Random, xml: bytes) -> bytes | None:
    """A sample count or hide_emitters of the integrator changed, or one added (also to an integrator that
    does not read it)."""
    action = rng.random()
    if action < 0.4 and (changed := _set_value(rng, xml, COUNT_RE, COUNTS)) is not None:
        return changed
    if action < 0.55 and (changed := _set_value(rng, xml, HIDE_RE, BOOLEANS)) is not None:
        return changed
    m = INTEGRATOR_RE.search(xml)
    if rng.random() < 0.15:
        prop = f'<boolean name="hide_emitters" value="{rng.choice(BOOLEANS)}"/>'
    else:
        prop = f'<integer name="{rng.choice(DIRECT_PROPERTIES)}" value="{rng.choice(COUNTS)}"/>'
    if m is None:  # no integrator: add a direct one
        scene = SCENE_OPEN_RE.search(xml)
        return _insert_after(xml, scene.end(), f'<integrator type="direct">{prop}</integrator>') if scene else None
    if m.group(1):  # <integrator .../>: open it
        return xml[: m.start()] + m.group(0)[:-2] + b">" + prop.encode() + b"</integrator>" + xml[m.end():]
    return _insert_after(xml, m.end(), prop)


def shape_emitter(rng: random.Random, xml: bytes) -> bytes | None:
    opens = list(SHAPE_OPEN_RE.finditer(xml))
    return _insert_after(xml, rng.choice(opens).end(), rng.choice(SHAPE_EMITTERS)) if opens else None


def top_emitter(rng: random.Random, xml: bytes) -> bytes | None:
    scene = SCENE_OPEN_RE.search(xml)
    return _insert_after(xml, scene.end(), rng.choice(TOP_EMITTERS)) if scene else None


def twosided(rng: random.Random, xml: bytes) -> bytes | None:
    """A diffuse BSDF wrapped in twosided BSDFs `depth` deep, or an odd twosided put in a shape or at the top."""
    bsdfs = list(BSDF_RE.finditer(xml))
    if bsdfs and rng.random() < 0.6:
        m = rng.choice(bsdfs)
        depth = rng.choice(DEPTHS)
        return xml[: m.start()] + b'<bsdf type="twosided">' * depth + m.group(0) + b"</bsdf>" * depth + xml[m.end():]
    opens = list(SHAPE_OPEN_RE.finditer(xml))
    if opens and rng.random() < 0.7:
        return _insert_after(xml, rng.choice(opens).end(), rng.choice(TWOSIDED))
    scene = SCENE_OPEN_RE.search(xml)
    return _insert_after(xml, scene.end(), rng.choice(TWOSIDED)) if scene else None


MUTATIONS = (("emitted", emitted_value, 0.3), ("spot-angle", spot_angle, 0.12), ("direction", direction, 0.06),
             ("direct-parameter", direct_parameter, 0.17), ("shape-emitter", shape_emitter, 0.12),
             ("top-emitter", top_emitter, 0.1), ("twosided", twosided, 0.13))


def mutate_light(rng: random.Random, xml: bytes) -> bytes:
    """One mutation of the emitters, the BSDFs or direct's parameters; where the one drawn finds nothing to
    change (no spot, no direction), an emitter is added instead."""
    _, op, _ = rng.choices(MUTATIONS, weights=[w for *_, w in MUTATIONS])[0]
    changed = op(rng, xml)
    if changed is None:
        changed = shape_emitter(rng, xml) if rng.random() < 0.5 else top_emitter(rng, xml)
    return xml if changed is None else changed
