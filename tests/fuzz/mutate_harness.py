"""Seeded mutations aimed at the harness around the renderers: what `images --scene` reads, prepares and hands
to Mitsuba before either renderer sees the file (mutate.py damages what the renderer reads).

Malformed and duplicated <default>s, huge tag names, ids and values, deep nesting, a missing sensor, film or
sampler, odd samplers, crop windows, mesh files with out-of-range indices, <include>s (of fragments, of
themselves, in cycles), Mitsuba 0.5 names, an <integer> for a float, forward references, two-sided wrappers,
filters, and binary garbage. Some write a file beside the scene (a mesh, an included fragment): each takes the
variant's folder. Given the same `random.Random`, a mutation is the same every time.
"""
from __future__ import annotations

import random
import re
from pathlib import Path

DEFAULTS = ['<default name="res"/>', '<default value="8"/>', '<default name="" value=""/>',
            '<default name="res" value="$res"/>', '<default name="res" value="abc"/>', '<default name="res" value="-1"/>',
            '<default name="res" value="0"/>', '<default name="res" value="1e9"/>', '<default name="res" value="nan"/>',
            '<default name="res" value="16384"/>', '<default name="spp" value="0"/>', '<default name="res" value="4"/>',
            '<default name="integrator" value="path"/>', '<default name="$res" value="8"/>',
            '<default name="res" value="8"><default name="res" value="9"/></default>']
SIZES = (1_000, 100_000, 1_000_000)
DEPTHS = (64, 500, 2_000, 10_000)
SAMPLERS = ["independent", "stratified", "multijitter", "ldsampler", "orthogonal", "correlated", "bogus", ""]
SAMPLER_PROPERTIES = ['<integer name="seed" value="7"/>', '<integer name="seed" value="-1"/>',
                      '<integer name="sample_count" value="0"/>', '<integer name="sample_count" value="-4"/>',
                      '<integer name="sample_count" value="1000000000"/>', '<float name="sample_count" value="4.5"/>',
                      '<boolean name="jitter" value="false"/>', '<integer name="sample_count" value="$spp"/>']
CROP_VALUES = ["0", "1", "-1", "3", "7", "64", "127", "128", "129", "100000", "2147483647", "nan", "1.5", "$res"]
PLY_INDICES = ("100000", "3", "-1", "4294967295", "2147483647")
FILTERS = ['<rfilter type="gaussian"><float name="stddev" value="3e9"/></rfilter>',
           '<rfilter type="gaussian"><float name="stddev" value="0"/></rfilter>',
           '<rfilter type="gaussian"><float name="stddev" value="-1"/></rfilter>', '<rfilter type="tent"/>',
           '<rfilter type="box"/>', '<rfilter type="lanczos"/>', '<rfilter type="tent"><float name="radius" '
           'value="1e9"/></rfilter>', '<rfilter type="bogus"/>']
LEGACY = [(b"to_world", b"toWorld"), (b"near_clip", b"nearClip"), (b"far_clip", b"farClip"),
          (b"sample_count", b"sampleCount"), (b'version="3.0.0"', b'version="0.5.0"'),
          (b'version="3.0.0"', b'version="2.0.0"'), (b'version="3.0.0"', b'version="abc"'), (b'version="3.0.0"', b""),
          (b"<float ", b"<integer "), (b"<rgb ", b"<spectrum "), (b"<rgb ", b"<color ")]

SCENE_OPEN_RE = re.compile(rb"<scene[^>]*>")
BLOCK_TAGS = (b"sensor", b"film", b"sampler", b"integrator", b"rfilter", b"emitter", b"bsdf", b"shape")
VALUE_RE = re.compile(rb'(value|id|name|type|filename)="([^"]*)"')


def _after_scene_open(xml: bytes, snippet: bytes) -> bytes:
    m = SCENE_OPEN_RE.search(xml)
    at = m.end() if m else 0
    return xml[:at] + snippet + xml[at:]


def _block(xml: bytes, tag: bytes) -> re.Match | None:
    """The first <tag ...>...</tag> or <tag .../> of the file (not nested in one of its own kind)."""
    return re.search(rb"<" + tag + rb"\b[^>]*/>|<" + tag + rb"\b[^>]*>.*?</" + tag + rb">", xml, re.S)


def bad_default(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    return _after_scene_open(xml, rng.choice(DEFAULTS).encode())


def huge(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """A tag name, an attribute value or an id of 1 kB to 1 MB."""
    size, action = rng.choice(SIZES), rng.random()
    if action < 0.35:
        return _after_scene_open(xml, b"<" + b"a" * size + b"/>")
    values = list(VALUE_RE.finditer(xml))
    if action < 0.7 and values:
        m = rng.choice(values)
        return xml[: m.start(2)] + rng.choice([b"x", b"1", b"9", b"\xc3\xa9"]) * size + xml[m.end(2):]
    return _after_scene_open(xml, b'<bsdf type="diffuse" id="' + b"i" * size + b'"/>')


def deep(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """Nested <bsdf>s (or nameless elements) thousands deep, inside a shape or at the top."""
    depth = rng.choice(DEPTHS)
    tag = rng.choice([b'bsdf type="twosided"', b'bsdf type="diffuse"', b"x", b'shape type="sphere"'])
    close = b"</" + tag.split()[0] + b">"
    nest = (b"<" + tag + b">") * depth + close * depth
    shape = _block(xml, b"shape")
    if shape is not None and rng.random() < 0.6 and not shape.group(0).endswith(b"/>"):
        end = shape.end() - len(b"</shape>")
        return xml[:end] + nest + xml[end:]
    return _after_scene_open(xml, nest)


def drop_block(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """No sensor, no film, no sampler, no integrator, no filter, or one emitter, BSDF or shape less."""
    tag = rng.choice(BLOCK_TAGS[:5] * 2 + BLOCK_TAGS[5:])
    m = _block(xml, tag)
    return xml[: m.start()] + xml[m.end():] if m else xml


def sampler(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    m = _block(xml, b"sampler")
    new = (f'<sampler type="{rng.choice(SAMPLERS)}">' + "".join(rng.sample(SAMPLER_PROPERTIES, rng.randint(0, 2)))
           + "</sampler>").encode()
    if m:
        return xml[: m.start()] + new + xml[m.end():]
    sensor = re.search(rb"<sensor\b[^>]*>", xml)
    return xml[: sensor.end()] + new + xml[sensor.end():] if sensor else xml


def crop(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    film = re.search(rb"<film\b[^>]*>", xml)
    if film is None or film.group(0).endswith(b"/>"):
        return xml
    names = rng.sample(["crop_offset_x", "crop_offset_y", "crop_width", "crop_height"], rng.randint(1, 4))
    props = "".join(f'<integer name="{n}" value="{rng.choice(CROP_VALUES)}"/>' for n in names).encode()
    return xml[: film.end()] + props + xml[film.end():]


def bad_mesh(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """A shape whose PLY (ASCII or binary) or OBJ names a vertex that is not there."""
    index = rng.choice(PLY_INDICES)
    kind = rng.choice(["ply", "ply-binary", "obj"])
    if kind == "obj":
        (folder / "badidx.obj").write_text(f"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {index}\n")
        name = "badidx.obj"
    else:
        header = ("ply\nformat {} 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n")
        if kind == "ply":
            body = f"0 0 0\n1 0 0\n0 1 0\n3 0 1 {index}\n".encode()
            data = header.format("ascii").encode() + body
        else:
            import struct
            body = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3I", 3, 0, 1, int(index) & 0xFFFFFFFF)
            data = header.format("binary_little_endian").encode() + body
        (folder / "badidx.ply").write_bytes(data)
        name = "badidx.ply"
    shape = f'<shape type="{name.split(".")[1]}"><string name="filename" value="{name}"/></shape>'.encode()
    return _after_scene_open(xml, shape)


def include(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """An <include> of a fragment, of a fragment that includes the scene back, of the scene itself, of a
    fragment that is not a scene, or of one nested fifty deep."""
    action = rng.random()
    scene_name = folder.name + ".xml"  # the variant's own file (fuzz_images.py names it after its folder)
    if action < 0.3:
        (folder / "inc.xml").write_text('<scene version="3.0.0"><shape type="sphere"><float name="radius" '
                                        'value="0.2"/></shape></scene>')
    elif action < 0.5:
        (folder / "inc.xml").write_text(f'<scene version="3.0.0"><include filename="{scene_name}"/></scene>')
    elif action < 0.6:
        return _after_scene_open(xml, f'<include filename="{scene_name}"/>'.encode())
    elif action < 0.75:
        (folder / "inc.xml").write_bytes(rng.choice([b"", b"<scene>", b"not xml", b"<shape type='sphere'/>",
                                                     b'<scene version="3.0.0"><sensor type="perspective"/></scene>']))
    else:
        for i in range(50):
            (folder / f"inc{i}.xml").write_text(f'<scene version="3.0.0"><include filename="inc{i + 1}.xml"/></scene>')
        (folder / "inc50.xml").write_text('<scene version="3.0.0"/>')
        (folder / "inc.xml").write_text('<scene version="3.0.0"><include filename="inc0.xml"/></scene>')
    return _after_scene_open(xml, b'<include filename="inc.xml"/>')


def legacy(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """Mitsuba 0.5 names, another version, a property of another type: what Mitsuba 3 upgrades or converts."""
    old, new = rng.choice(LEGACY)
    return xml.replace(old, new) if rng.random() < 0.6 else xml.replace(old, new, 1)


def wrap_bsdf(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """A BSDF wrapped in a twosided, or defined after its first <ref> (a forward reference)."""
    m = re.search(rb'<bsdf type="diffuse"[^>]*/>|<bsdf type="diffuse"[^>]*>.*?</bsdf>', xml, re.S)
    if m is None:
        return xml
    if rng.random() < 0.5:
        return xml[: m.start()] + b'<bsdf type="twosided">' + m.group(0) + b"</bsdf>" + xml[m.end():]
    named = re.sub(rb"<bsdf ", b'<bsdf id="fwd" ', m.group(0), count=1)
    body = xml[: m.start()] + b'<ref id="fwd"/>' + xml[m.end():]
    end = body.rfind(b"</scene>")
    return body[:end] + named + body[end:] if end >= 0 else body + named


def rfilter(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    new = rng.choice(FILTERS).encode()
    m = _block(xml, b"rfilter")
    if m:
        return xml[: m.start()] + new + xml[m.end():]
    film = re.search(rb"<film\b[^>]*>", xml)
    return xml[: film.end()] + new + xml[film.end():] if film and not film.group(0).endswith(b"/>") else xml


def garbage(rng: random.Random, xml: bytes, folder: Path) -> bytes:
    """Random bytes, NULs or invalid UTF-8 inside the XML, a UTF-16 copy, or control characters in a value."""
    action = rng.random()
    if action < 0.3:
        return rng.randbytes(rng.choice((0, 1, 100, 10_000)))
    if action < 0.5:
        pos = rng.randrange(len(xml) + 1)
        return xml[:pos] + rng.choice([b"\x00", b"\xff\xfe", b"\xc3\x28", b"\x1b[31m", b"\x07\x08"]) * 5 + xml[pos:]
    if action < 0.65:
        return xml.decode(errors="replace").encode("utf-16")
    values = list(VALUE_RE.finditer(xml))
    if not values:
        return xml
    m = rng.choice(values)
    odd = rng.choice([b"\x01\x02", b"[red]x[/red]", b"]]>", b"&#0;", b"&lt;&amp;"])  # control, markup, entities
    return xml[: m.start(2)] + odd + xml[m.end(2):]


MUTATIONS = {"default": (bad_default, 1.0), "huge": (huge, 0.6), "deep": (deep, 0.6), "drop": (drop_block, 1.2),
             "sampler": (sampler, 0.8), "crop": (crop, 0.8), "mesh-index": (bad_mesh, 0.6), "include": (include, 0.8),
             "legacy": (legacy, 1.0), "bsdf": (wrap_bsdf, 0.6), "rfilter": (rfilter, 0.6), "garbage": (garbage, 0.5)}


def mutate_for_harness(rng: random.Random, xml: bytes, folder: Path) -> tuple[bytes, str]:
    """One or two harness-aimed mutations of a scene file (files they need are written into `folder`)."""
    names = list(MUTATIONS)
    done = []
    for _ in range(rng.choice((1, 1, 2))):
        name = rng.choices(names, weights=[MUTATIONS[n][1] for n in names])[0]
        xml = MUTATIONS[name][0](rng, xml, folder)
        done.append(name)
    return xml, "+".join(done)
