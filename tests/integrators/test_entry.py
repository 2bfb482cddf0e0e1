"""The integrator entries (harness/integrators/) and their registry: found from the package and from
$MCVAL_INTEGRATOR_PATH, matched with the renderer's integrators, and what the suite derives from them."""
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import harness.integrators.registry as registry
from harness.engines.mitsuba_integrators import mitsuba_mapping
from harness.engines.mitsuba_scene import mitsuba_xml
from harness.images.suite import (INTEGRATORS, REFERENCE_SPP, TESTED_SPP, ImageCase, not_applicable_cases,
                                  select_cases)
from harness.integrators import entries, match
from harness.report.integrator_table import integrators_table
from tests.helpers.registered_integrators import PRODUCT

ROOT = Path(__file__).resolve().parents[2]
CORNELL_BOX = ROOT / "scenes" / "real" / "cornell_box.xml"
EXTRA = '''from harness.integrators.entry import IntegratorEntry
ENTRY = IntegratorEntry(name="{name}", tested_spp=2, reference_spp=8)
'''
#: The integrators of this repository's renderer (Engine.integrators).
RENDERER = tuple(PRODUCT)


@pytest.fixture
def extra_folder(tmp_path, monkeypatch):
    """A folder on $MCVAL_INTEGRATOR_PATH; write entries into it."""
    monkeypatch.setenv(registry.PATH_ENV, str(tmp_path))
    return tmp_path


def test_every_integrator_of_the_product_has_its_entry_and_no_other():
    assert set(entries()) == set(RENDERER) >= {"normals", "simple", "ao"}
    from harness.engines.registry import engine_integrators
    assert set(engine_integrators("mcval")) == set(RENDERER)
    m = match(engine_integrators("mcval"))
    assert [e.name for e in m.entries] and m.without_entry == ()
    assert {e.source for e in m.entries} == {f"harness/integrators/{n}.py" for n in RENDERER}


def test_suite_views_are_the_entries_budgets():
    assert INTEGRATORS[0] == "normals"  # first on every scene: its failure notes a camera or geometry mismatch
    assert set(INTEGRATORS) == set(RENDERER) and len(INTEGRATORS) == len(RENDERER)
    assert dict(TESTED_SPP) == {name: entries()[name].tested_spp for name in RENDERER}
    assert {name: TESTED_SPP[name] for name in ("normals", "simple", "ao")} == {"normals": 16, "simple": 32, "ao": 32}
    assert {name: REFERENCE_SPP[name] for name in ("normals", "simple", "ao")} == {"normals": 64, "simple": 256,
                                                                                 "ao": 256}


def test_a_heavy_tailed_scene_of_the_suite_takes_more_tested_samples():
    assert ImageCase("cornell", "simple").test_spp == TESTED_SPP["simple"]
    assert ImageCase("close_light", "ao").test_spp == TESTED_SPP["ao"]  # no light near a wall under ao
    assert ImageCase("close_light", "direct").test_spp == 16 * TESTED_SPP["direct"]
    assert ImageCase("close_light", "simple", group="user").test_spp == TESTED_SPP["simple"]  # a user's is not ours
    assert ImageCase("close_light", "simple", spp=20).test_spp == 20  # a budget chose them


def test_only_the_suites_heavy_tailed_cases_go_without_the_firefly_test():
    assert ImageCase("close_light", "path").heavy_tail.startswith("light off the wall")
    assert ImageCase("close_light", "direct").heavy_tail == ""
    assert ImageCase("cornell", "path").heavy_tail.startswith("green light on the red wall")
    assert ImageCase("cornell", "direct").heavy_tail == ""
    assert ImageCase("cornell_measured", "path", group="real").heavy_tail.startswith("green light")
    assert ImageCase("cornell_box", "path", group="real").heavy_tail == ""
    assert ImageCase("close_light", "path", group="user").heavy_tail == ""  # a user's is not ours


def test_an_entry_from_the_path_is_found_and_an_error_without_a_renderer_integrator(extra_folder):
    (extra_folder / "sparkle.py").write_text(EXTRA.format(name="sparkle"))
    assert entries()["sparkle"].source == str(extra_folder / "sparkle.py")
    with pytest.raises(ValueError, match=r"sparkle\.py: entry for integrator 'sparkle', which the tested engine"):
        match(RENDERER)


def test_a_renderer_integrator_without_entry_is_listed_not_dropped(mitsuba):
    m = match((*RENDERER, "sparkle"))
    assert m.without_entry == ("sparkle",) and len(m.entries) == len(RENDERER)
    from rich.console import Console
    console = Console(width=200, record=True)
    console.print(integrators_table(m, mitsuba))
    assert "no harness entry" in [line for line in console.export_text().splitlines() if "sparkle" in line][0]


def test_duplicate_and_missing_entries_name_their_files(extra_folder):
    (extra_folder / "again.py").write_text(EXTRA.format(name="ao"))
    with pytest.raises(ValueError, match=r"again\.py: integrator 'ao' already has an entry in harness/"):
        entries()
    (extra_folder / "again.py").write_text("X = 1\n")
    with pytest.raises(ValueError, match=r"again\.py: no ENTRY"):
        entries()


def test_a_path_folder_that_does_not_exist_is_an_error(monkeypatch, tmp_path):
    monkeypatch.setenv(registry.PATH_ENV, str(tmp_path / "nowhere"))
    with pytest.raises(ValueError, match="nowhere is not a folder"):
        entries()


def _mapped(integrator: str) -> ET.Element:
    return ET.fromstring(mitsuba_xml(CORNELL_BOX.read_text(), integrator))


@pytest.mark.parametrize("integrator", ["normals", "ao"])
def test_mitsuba_mapping_removes_the_area_emitter_but_keeps_its_shape(integrator):
    root = _mapped(integrator)
    assert not [e for s in root.iter("shape") for e in s.iter("emitter")]
    assert "light" in {s.get("id") for s in root.iter("shape")}
    assert [e.get("type") for e in root.findall("integrator")] == [mitsuba_mapping(integrator).plugin]
    assert [e.get("type") for e in root.findall("emitter")] == (["constant"] if integrator == "ao" else [])


def test_simple_on_the_cornell_box_is_not_applicable_not_run():
    assert "cornell_box:simple" not in {c.key for c in select_cases(None)}
    assert {c.key for c in select_cases(["cornell_box"])} == {f"cornell_box:{n}" for n in PRODUCT if n != "simple"}
    assert [(c.key, why) for c, why in not_applicable_cases(None)] == [
        ("furnace:ao", "a furnace: the camera is enclosed, no environment reaches it"),
        ("furnace:simple", "no point light")] + [
        (f"{scene}:simple", "no point light")
        for scene in ("materials", "plane_disk_light", "plane_rect_light", "plane_sphere_light", "cornell_box",
                      "cornell_measured")]
    with pytest.raises(ValueError, match="cornell_box:simple is not applicable: no point light"):
        select_cases(["cornell_box:simple"])


def test_real_cases_live_in_scenes_real():
    case = ImageCase("cornell_box", "ao", "real")
    assert case.path == CORNELL_BOX
    assert next(c for c in select_cases(["cornell_box:ao"])) == case


def test_the_integrators_command_lists_each_with_its_entry(capsys):
    from harness.cli import main
    assert main(["integrators"]) == 0
    out = capsys.readouterr().out
    for name, mitsuba in (("normals", "aov(aovs=nn:sh_normal)"), ("simple", "direct(emitter_samples=1,"),
                          ("ao", "direct(hide_emitters=true, emitter_samples=0, bsdf_samples=1)")):
        row = next(line for line in out.splitlines() if line.strip().startswith(name + " "))
        assert f"harness/integrators/{name}.py" in row and mitsuba in row, out
    assert "no harness entry" not in out


def test_an_orphan_entry_makes_the_integrators_command_fail_naming_it(extra_folder, capsys):
    from harness.cli import main
    (extra_folder / "sparkle.py").write_text(EXTRA.format(name="sparkle"))
    assert main(["integrators"]) == 2
    assert "sparkle.py: entry for integrator 'sparkle'" in capsys.readouterr().err.replace("\n", "")


def test_a_scene_the_harness_cannot_parse_is_left_to_the_renderer_to_report(tmp_path):
    broken = tmp_path / "broken.xml"
    broken.write_text("<scene><shape type=")
    assert entries()["simple"].not_applicable(broken) is None
    broken.write_text('<scene><emitter type="constant"/></scene>')
    assert entries()["simple"].not_applicable(broken) == "no point light"
