"""Edits of a scene's tree that keep its lines: Mitsuba's errors about the scene it was given then name lines
of the prepared copy, which map to the user's file."""
import xml.etree.ElementTree as ET

import pytest

from harness.engines.mitsuba_scene import mitsuba_xml
from harness.engines.xml_lines import remove_keeping_lines, replace_keeping_lines
from harness.images.suite import INTEGRATORS, SCENES_DIR

TEXT = """<scene>
  <a>
    <b />
  </a>
  <c />
  <d />
</scene>"""


def _line(text: str, tag: str) -> int:
    return text[:text.index(f"<{tag}")].count("\n") + 1


@pytest.mark.parametrize("gone", ["a", "c"])
def test_what_follows_a_removed_element_keeps_its_line(gone):
    root = ET.fromstring(TEXT)
    remove_keeping_lines(root, root.find(gone))
    written = ET.tostring(root, encoding="unicode")
    assert _line(written, "d") == _line(TEXT, "d") and f"<{gone}" not in written


def test_what_follows_a_replaced_element_keeps_its_line():
    root = ET.fromstring(TEXT)
    new = ET.Element("e")
    ET.SubElement(new, "f")
    replace_keeping_lines(root, root.find("a"), new)
    written = ET.tostring(root, encoding="unicode")
    assert _line(written, "e") == _line(TEXT, "a") and _line(written, "d") == _line(TEXT, "d")


@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("scene", ["plane_point", "cornell"])
def test_mitsubas_copy_of_a_scene_keeps_every_elements_line(scene, integrator):
    """Every element of the scene that Mitsuba's copy keeps starts on the line it started on."""
    from harness.engines.nori.lined_xml import parse_lined

    text = ET.tostring(ET.parse(SCENES_DIR / f"{scene}.xml").getroot(), encoding="unicode")
    before = parse_lined(text, SCENES_DIR / scene)
    after = parse_lined(mitsuba_xml(text, integrator), SCENES_DIR / scene)
    where: dict[tuple, set[int]] = {}
    for e in before.root.iter():
        where.setdefault((e.tag, tuple(sorted(e.attrib.items()))), set()).add(before.line(e))
    kept = [(e, where.get((e.tag, tuple(sorted(e.attrib.items()))))) for e in after.root.iter()]
    assert sum(lines is not None for _, lines in kept) > 10
    for e, lines in kept:
        assert lines is None or after.line(e) in lines, (e.tag, e.attrib, after.line(e), lines)
