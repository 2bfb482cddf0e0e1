"""Seeded mutations of scene files and their meshes, for the fuzz driver.

Each mutation is a small, plausible damage a user or a broken exporter could
make: a number replaced by an extreme or non-finite value, an element dropped,
duplicated or retyped, an emitter, a BSDF or direct's parameters damaged
(mutate_lights.py), a file truncated or its bytes flipped, a PLY header that
lies about its counts or types, a mesh path that names a FIFO, a folder or
nothing. Given the same `random.Random`, a mutation is the same every time.
"""
from __future__ import annotations

import random
import re
import struct
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # also when imported as tests.fuzz.mutate
from mutate_lights import mutate_light  # noqa: E402

#: Values a number is replaced by: non-finite, extreme, boundary and malformed.
NUMBERS = ["nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e39", "-1e39", "3.4e38", "1e30", "-1e30", "1e20",
           "1e-45", "1e-30", "0", "-0", "-1", "1", "0.5", "2", "180", "360", "1e6", "2147483647", "-2147483648",
           "4294967296", "9999999999999", "0x1p3", "1,2", "1 2 3 4", "", " ", "abc", "$missing", "1e", "--1",
           "16384", "16385", "100000", "1024", "1025", "0.01", "0.049", "4.01", "179.95", "1e15", "1.1e15"]
#: Types an element's type attribute is changed to: mcval's, Mitsuba's that we lack, nonsense.
TYPES = ["point", "constant", "area", "spot", "directional", "envmap", "projector", "twosided", "obj", "ply",
         "rectangle", "cube", "sphere", "disk", "cylinder", "serialized", "diffuse", "conductor", "box", "gaussian",
         "tent", "independent", "stratified", "multijitter", "perspective", "orthographic", "hdrfilm", "normals",
         "simple", "ao", "path", "direct", "", "$missing"]
#: Mesh file names that must be refused cleanly (the driver creates FIFO, DIR and BIG in the work folder).
FILENAMES = ["/dev/zero", "/dev/null", "/dev/urandom", "FIFO", "DIR", "missing.ply", "x" * 5000 + ".ply",
             "../" * 40 + "etc/passwd", "", ".", "meshes", "meshes/sphere.ply/..", "mesh.obj", "mesh.ply"]
#: Snippets inserted at a random element boundary.
SNIPPETS = ['<shape type="cube"/>', '<emitter type="point"/>', '<emitter type="constant"/>', '<emitter type="spot"/>',
            '<emitter type="directional"/>', '<emitter type="area"/>', '<bsdf type="twosided"/>',
            '<integrator type="direct"><integer name="emitter_samples" value="0"/></integrator>',
            '<float name="fov" value="30"/>', '<transform name="to_world"><scale value="0"/></transform>',
            '<integrator type="ao"><integer name="samples" value="1024"/></integrator>', '<bsdf type="diffuse"/>',
            '<sensor type="perspective"><float name="fov" value="30"/></sensor>', '<ref id="nothing"/>',
            '<rgb name="reflectance" value="0.5"/>', '<!-- c -->', '<![CDATA[x]]>', '<default name="res" value="8"/>',
            '<shape type="ply"><string name="filename" value="meshes/sphere.ply"/></shape>', '&amp;', '<',
            '<shape type="sphere"><float name="radius" value="1e-3"/><point name="center" value="0, 1, 0"/></shape>',
            # The scene's own file (a cycle), the special files and folders, a missing one.
            '<include filename="scene.xml"/>', '<include filename="FIFO"/>', '<include filename="DIR"/>',
            '<include filename="mesh.obj"/>', '<include filename="missing.xml"/>', '<include filename="/dev/zero"/>',
            '<path value="DIR"/>', '<path value="FIFO"/>', '<path value="meshes"/>', '<path value="$missing"/>']

NUMBER_RE = re.compile(rb"-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
ATTR_RE = re.compile(rb'(value|angle|x|y|z|origin|target|up)="([^"]*)"')
TYPE_RE = re.compile(rb'type="([^"]*)"')
FILENAME_RE = re.compile(rb'(name="filename"\s+value=")([^"]*)(")')
ELEMENT_RE = re.compile(rb"<(?!/|!|\?)[^<>]*/>|<(?!/|!|\?)[^<>]*>")


def _replace_span(data: bytes, span: tuple[int, int], new: bytes) -> bytes:
    return data[: span[0]] + new + data[span[1]:]


def mutate_number(rng: random.Random, xml: bytes) -> bytes:
    """One number inside an attribute value becomes an extreme, non-finite or malformed one."""
    attrs = list(ATTR_RE.finditer(xml))
    if not attrs:
        return xml
    m = rng.choice(attrs)
    value = m.group(2)
    numbers = list(NUMBER_RE.finditer(value))
    new = rng.choice(NUMBERS).encode()
    if numbers and rng.random() < 0.7:
        n = rng.choice(numbers)
        value = _replace_span(value, n.span(), new)
    else:
        value = new
    return _replace_span(xml, m.span(2), value)


def mutate_type(rng: random.Random, xml: bytes) -> bytes:
    types = list(TYPE_RE.finditer(xml))
    return _replace_span(xml, rng.choice(types).span(1), rng.choice(TYPES).encode()) if types else xml


def mutate_filename(rng: random.Random, xml: bytes) -> bytes:
    names = list(FILENAME_RE.finditer(xml))
    return _replace_span(xml, names[rng.randrange(len(names))].span(2), rng.choice(FILENAMES).encode()) \
        if names else xml


def mutate_element(rng: random.Random, xml: bytes) -> bytes:
    """Drop, duplicate or insert an element (self-closing ones keep the XML well formed)."""
    elements = list(ELEMENT_RE.finditer(xml))
    if not elements:
        return xml
    m = rng.choice(elements)
    action = rng.random()
    if action < 0.35 and m.group(0).endswith(b"/>"):
        return _replace_span(xml, m.span(), b"")
    if action < 0.6:
        return xml[: m.start()] + m.group(0) + xml[m.start():] if m.group(0).endswith(b"/>") else xml
    return xml[: m.start()] + rng.choice(SNIPPETS).encode() + xml[m.start():]


def mutate_bytes(rng: random.Random, data: bytes) -> bytes:
    """Truncate, flip, delete or repeat bytes: damage with no respect for the format."""
    if not data:
        return data
    action = rng.random()
    pos = rng.randrange(len(data))
    if action < 0.3:
        return data[:pos]
    if action < 0.6:
        out = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            i = rng.randrange(len(out))
            out[i] = rng.randrange(256)
        return bytes(out)
    if action < 0.8:
        return data[:pos] + data[pos + rng.randint(1, 64):]
    chunk = data[pos: pos + rng.randint(1, 64)]
    return data[:pos] + chunk * rng.randint(2, 50) + data[pos:]


def mutate_xml(rng: random.Random, xml: bytes) -> tuple[bytes, str]:
    """One to three mutations of a scene file; returns the bytes and what was done."""
    ops = [("number", mutate_number, 0.45), ("type", mutate_type, 0.12), ("filename", mutate_filename, 0.08),
           ("element", mutate_element, 0.2), ("bytes", mutate_bytes, 0.15), ("light", mutate_light, 0.25)]
    done = []
    for _ in range(rng.choice((1, 1, 1, 2, 3))):
        name, op, _ = rng.choices(ops, weights=[w for *_, w in ops])[0]
        xml = op(rng, xml)
        done.append(name)
    return xml, "+".join(done)


def _ply_header(data: bytes) -> tuple[bytes, bytes]:
    end = data.find(b"end_header\n")
    return (data, b"") if end < 0 else (data[: end + 11], data[end + 11:])


def mutate_ply(rng: random.Random, data: bytes) -> tuple[bytes, str]:
    """A PLY damaged in its header (counts, types, format), its indices, its floats, or its length."""
    header, body = _ply_header(data)
    action = rng.random()
    if action < 0.2:  # a count that lies
        counts = list(re.finditer(rb"(element \w+ )(\d+)", header))
        if counts:
            m = rng.choice(counts)
            new = rng.choice([b"0", b"1", b"2", b"4294967295", b"2147483648", b"99999999999", b"-1",
                              str(int(m.group(2)) * rng.choice((2, 1000))).encode(),
                              str(max(0, int(m.group(2)) - 1)).encode()])
            return _replace_span(header, m.span(2), new) + body, "ply-count"
    if action < 0.35:  # a type or format that lies
        words = list(re.finditer(rb"\b(float|double|uchar|uint|int|binary_little_endian|binary_big_endian|ascii|"
                                 rb"vertex_indices|list|x|nx)\b", header))
        if words:
            m = rng.choice(words)
            new = rng.choice([b"float", b"double", b"uchar", b"int", b"uint", b"short", b"int64", b"binary_big_endian",
                              b"ascii", b"bogus", b"list uchar int", b"vertex_index", b"", b"x"])
            return _replace_span(header, m.span(), new) + body, "ply-type"
    if action < 0.55 and len(body) >= 4:  # an index or coordinate with an extreme value
        pos = rng.randrange(0, len(body) - 3) & ~3
        value = rng.choice([struct.pack("<I", rng.choice((0xFFFFFFFF, 0x7FFFFFFF, 1 << 20, 123456))),
                            struct.pack("<f", float("nan")), struct.pack("<f", float("inf")),
                            struct.pack("<f", 3e38), struct.pack("<i", -1), b"\xff\x00\x00\x00"])
        return header + body[:pos] + value + body[pos + 4:], "ply-value"
    if action < 0.75:  # truncated: in the data or inside the header
        cut = rng.randrange(len(data)) if rng.random() < 0.7 else rng.randrange(max(1, len(header)))
        return data[:cut], "ply-truncate"
    return mutate_bytes(rng, data), "ply-bytes"


def mutate_obj(rng: random.Random, text: bytes) -> tuple[bytes, str]:
    """An OBJ with an index out of range, a NaN coordinate, a malformed line, or cut short."""
    lines = text.split(b"\n")
    i = rng.randrange(len(lines))
    action = rng.random()
    if action < 0.3:
        lines[i] = rng.choice([b"f 1 2 99999", b"f 0 1 2", b"f -99 1 2", b"f 1/1/1 2//2 3", b"f 1", b"f 1 2",
                               b"f 4294967296 1 2", b"f a b c", b"f 1 2 3 4 5 6 7 8 9"])
    elif action < 0.55:
        lines[i] = rng.choice([b"v nan 0 0", b"v inf 1 1", b"v 1e39 0 0", b"v 1", b"v", b"vn 0 0 0", b"vn nan 0 1",
                               b"vt 0.5", b"mtllib missing.mtl", b"usemtl x", b"o", b"g"])
    elif action < 0.75:
        return text[: rng.randrange(len(text))], "obj-truncate"
    else:
        return mutate_bytes(rng, text), "obj-bytes"
    return b"\n".join(lines), "obj-line"
