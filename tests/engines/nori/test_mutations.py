"""Seeded damage to scene files (tests/fuzz/mutate.py's values) through both translations: each damaged file is
translated with finite numbers or refused with one NoriSceneError line naming the file; nothing else escapes."""
import math
import random
import xml.etree.ElementTree as ET

import pytest

from harness.engines.nori.lined_xml import NoriSceneError
from harness.engines.nori.to_mitsuba import nori_to_mitsuba
from harness.engines.nori.to_nori import written_nori_scene
from harness.engines.nori.values import numbers
from harness.images.suite import SCENES_DIR
from tests.engines.nori.test_round_trip import EMITTERS, MCVAL_OF_NORI, nori_file
from tests.fuzz.mutate import NUMBERS, TYPES

RUNS = 150


def damaged(text: str, rng: random.Random) -> str:
    """`text` with one attribute value replaced by a hard number or a wrong type."""
    root = ET.fromstring(text)
    element = rng.choice([e for e in root.iter() if e.attrib])
    key = rng.choice(sorted(element.attrib))
    element.set(key, rng.choice(TYPES if key == "type" else NUMBERS))
    return ET.tostring(root, encoding="unicode")


NUMERIC_KEYS = ("value", "x", "y", "z", "angle", "origin", "target", "up")


def assert_finite(root: ET.Element) -> None:
    """Every number the translation wrote is finite (strings and booleans are not numbers)."""
    for e in root.iter():
        if e.tag in ("string", "boolean"):
            continue
        for key, value in e.attrib.items():
            if key in NUMERIC_KEYS:
                values = numbers(value)
                assert values is not None and all(math.isfinite(v) for v in values), (e.tag, e.attrib)


@pytest.mark.parametrize("integrator", sorted(EMITTERS))
def test_damaged_nori_files_are_translated_or_refused_in_one_line(tmp_path, integrator):
    path = nori_file(tmp_path, integrator)
    good = path.read_text()
    rng = random.Random(f"nori-{integrator}")
    for _ in range(RUNS):
        path.write_text(damaged(good, rng))
        try:
            assert_finite(nori_to_mitsuba(path.read_text(), path))
        except NoriSceneError as e:
            assert str(e).startswith(f"{path}:") and "\n" not in str(e)


@pytest.mark.parametrize("scene", ["plane_point", "cornell", "mesh_no_normals"])
def test_damaged_suite_scenes_are_written_for_nori_or_refused_in_one_line(tmp_path, scene):
    source = SCENES_DIR / f"{scene}.xml"
    good = source.read_text()
    rng = random.Random(f"mitsuba-{scene}")
    (tmp_path / "meshes").symlink_to(SCENES_DIR / "meshes")  # the copy finds the scene's meshes
    path = tmp_path / source.name
    for _ in range(RUNS):
        path.write_text(damaged(good, rng))
        mcval = rng.choice(sorted(MCVAL_OF_NORI.values()))
        try:
            text, *_ = written_nori_scene(path, {"res": "16"}, mcval, rng.choice([mcval, "direct"]), 2)
            assert_finite(ET.fromstring(text))
        except (NoriSceneError, ValueError) as e:
            assert "\n" not in str(e) and str(path.parent) in str(e), str(e)
