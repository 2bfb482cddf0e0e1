"""Nori's test files read as they are: BSDF tests (`<test type="chi2test">`, `<test type="ttest">` of `<bsdf>`s) and
scene tests (a `<test type="ttest">` of `<scene>`s, each with its reference): the test's properties with Nori's
defaults, each `<bsdf>` with its properties, each `<scene>` as its element (harness/engines/nori/to_mitsuba.py reads
it). A refusal is one line, "FILE:LINE: <element>: why"."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from harness.engines.nori.lined_xml import LinedXml, NoriSceneError, parse_lined
from harness.engines.nori.values import numbers

#: The test types read, and each one's properties with Nori's defaults (src/chi2test.cpp, src/ttest.cpp).
DEFAULTS = {
    "chi2test": {"significanceLevel": 0.01, "resolution": 10, "minExpFrequency": 5, "sampleCount": -1,
                 "testCount": 5},
    "ttest": {"significanceLevel": 0.01, "angles": "", "references": "", "sampleCount": 100_000},
}
#: Nori's property elements and how many numbers each holds.
_VALUE_TAGS = {"float": 1, "integer": 1, "color": 3, "boolean": 0, "string": 0}
#: The largest file read (Nori's are under 1 KB).
MAX_BYTES = 1 << 20


@dataclass(frozen=True)
class NoriBsdf:
    """A `<bsdf>` of a test file: its type, its properties (numbers: one, or three for a colour) and where it is."""

    type: str
    properties: dict[str, tuple[float, ...]]
    where: str


@dataclass(frozen=True)
class NoriTest:
    """A test file: its kind ("chi2test" or "ttest"), its properties (Nori's defaults where absent), its BSDFs."""

    path: Path
    kind: str
    properties: dict[str, float | str]
    bsdfs: list[NoriBsdf] = field(default_factory=list)
    #: A scene ttest's `<scene>` elements, in order, and the parsed file they belong to (their lines).
    scenes: list = field(default_factory=list)
    doc: LinedXml | None = None

    def floats(self, name: str) -> list[float]:
        """A ttest's list property ("angles", "references") as numbers."""
        text = str(self.properties[name]).strip()
        return numbers(text) or [] if text else []


def _value(doc: LinedXml, e, kind: str) -> tuple[str, float | str | tuple[float, ...]]:
    name, value = e.get("name"), e.get("value")
    if not name or value is None:
        raise doc.fail(e, "expected name=\"...\" and value=\"...\"")
    if kind in ("string", "boolean"):
        return name, value
    parsed = numbers(value)
    if parsed is None or len(parsed) != _VALUE_TAGS[kind]:
        raise doc.fail(e, f"expected {'three finite numbers' if kind == 'color' else 'a finite number'}")
    if kind == "integer" and not float(parsed[0]).is_integer():
        raise doc.fail(e, "expected an integer")
    return name, tuple(parsed)


def _bsdf(doc: LinedXml, e) -> NoriBsdf:
    if not e.get("type"):
        raise doc.fail(e, "expected type=\"...\" (e.g. microfacet)")
    properties = {}
    for child in e:
        if child.tag not in _VALUE_TAGS or child.tag in ("string", "boolean"):
            raise doc.fail(child, "expected a number property of the BSDF (<float>, <integer>, <color>)")
        name, value = _value(doc, child, child.tag)
        properties[name] = value
    return NoriBsdf(e.get("type"), properties, doc.where(e))


def read_nori_test(path: Path) -> NoriTest:
    """The test file at `path`; NoriSceneError (a ValueError) saying where and why it cannot be read."""
    path = Path(path)
    if not path.is_file():
        raise NoriSceneError(f"{path}: no such file")
    if path.stat().st_size > MAX_BYTES:
        raise NoriSceneError(f"{path}: {path.stat().st_size} bytes: not a Nori test file (at most {MAX_BYTES})")
    doc = parse_lined(path.read_text(errors="replace"), path)
    root = doc.root
    if root.tag != "test" or root.get("type") not in DEFAULTS:
        raise doc.fail(root, f"expected <test type=\"...\"> of type {' or '.join(DEFAULTS)}")
    kind = root.get("type")
    properties: dict[str, float | str] = dict(DEFAULTS[kind])
    bsdfs, scenes = [], []
    for e in root:
        if e.tag == "bsdf":
            bsdfs.append(_bsdf(doc, e))
        elif e.tag == "scene" and kind == "ttest":
            scenes.append(e)
        elif e.tag in _VALUE_TAGS:
            name, value = _value(doc, e, e.tag)
            if name not in properties:
                raise doc.fail(e, f"{kind} has no property {name!r} (it has {', '.join(properties)})")
            properties[name] = value if isinstance(value, str) else value[0]
        else:
            raise doc.fail(e, f"expected <bsdf> or a property of the {kind}")
    if bsdfs and scenes:
        raise doc.fail(scenes[0], "a test of BSDFs and scenes at once (Nori refuses it too)")
    if not bsdfs and not scenes:
        raise doc.fail(root, f"no {'<bsdf> or <scene>' if kind == 'ttest' else '<bsdf>'} to test")
    test = NoriTest(path, kind, properties, bsdfs, scenes, doc)
    if scenes:
        references = test.floats("references")
        if len(references) != len(scenes):
            raise doc.fail(root, f"expected one reference per scene: {len(scenes)} scenes, {len(references)} "
                                 "references")
    elif kind == "ttest":
        angles, references = test.floats("angles"), test.floats("references")
        if not angles or len(references) != len(angles) * len(bsdfs):
            raise doc.fail(root, f"expected one reference per angle and BSDF: {len(angles)} angles x {len(bsdfs)} "
                           f"BSDFs, {len(references)} references")
    return test
