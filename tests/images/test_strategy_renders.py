"""The strategy check's renders (harness/images/strategy_renders.py): which cases compare their strategies and
why the others do not; the scene copy that selects a strategy; the case's own render standing for MIS."""
from __future__ import annotations

import xml.etree.ElementTree as ET

from harness.engines.base import Engine
from harness.images.strategy_renders import default_strategy, not_judged, strategy_scene, strategy_seed
from harness.images.suite import ROOT, ImageCase

SCENES = ROOT / "scenes"


class Reader(Engine):
    """An engine that reads (or not) the parameters of a scene file's <integrator>."""

    name = "reader"

    def __init__(self, reads: bool = True) -> None:
        self.reads = reads

    def reads_integrator_parameters(self, integrator: str) -> bool:
        return self.reads

    def version(self) -> str:
        return "test"


def test_direct_on_an_area_light_compares_its_strategies():
    assert not_judged(ImageCase("plane_rect_light", "direct"), Reader()) is None


def test_the_reasons_a_case_does_not():
    assert not_judged(ImageCase("plane_rect_light", "ao"), Reader()) == "no strategies"
    assert not_judged(ImageCase("plane_rect_light", "direct"), Reader(reads=False)) == \
        "reader takes no direct bsdf_samples or emitter_samples from a scene file"
    # cornell: point lights beside its environment, which only emitter samples find.
    assert not_judged(ImageCase("cornell", "direct"), Reader()) == \
        "the strategies see different light: point lights, which BSDF sampling never finds"


def test_mcval_and_mitsuba_read_directs_parameters_from_the_file(mcval, mitsuba):
    assert mcval.reads_integrator_parameters("direct")
    assert mitsuba.reads_integrator_parameters("direct")
    assert not mitsuba.reads_integrator_parameters("ao")  # set values: direct with bsdf_samples 1


def test_only_our_renderer_reads_paths_strategy(mcval, mitsuba):
    """Mitsuba's path has no `strategy` (its copy leaves it out), nor a Mitsuba-dialect engine file's renderer."""
    assert mcval.reads_integrator_parameters("path")
    assert not mitsuba.reads_integrator_parameters("path")
    assert not_judged(ImageCase("plane_rect_light", "path"), mitsuba) == \
        "mitsuba takes no path strategy from a scene file"
    assert not_judged(ImageCase("plane_rect_light", "path"), mcval) is None


def test_a_path_strategy_copy_keeps_the_files_depth(tmp_path):
    copy = strategy_scene(SCENES / "furnace.xml", "path", (("string", "strategy", "ems"),), tmp_path / "out.xml")
    (integrator,) = ET.parse(copy).getroot().iter("integrator")
    assert {e.get("name"): e.get("value") for e in integrator} == {"max_depth": "8", "rr_depth": "5", "strategy": "ems"}
    # The case's own render is path's MIS at the file's depth: not rendered twice.
    assert default_strategy(ImageCase("furnace", "path"), SCENES / "furnace.xml") == "mis"


def test_the_copy_sets_the_strategy_and_keeps_the_rest(tmp_path):
    scene = tmp_path / "lit.xml"
    scene.write_text((SCENES / "plane_rect_light.xml").read_text().replace(
        '<integrator type="$integrator"/>',
        '<integrator type="direct"><boolean name="hide_emitters" value="true"/>'
        '<integer name="shading_samples" value="4"/></integrator>'))
    copy = strategy_scene(scene, "direct", (("integer", "emitter_samples", "0"), ("integer", "bsdf_samples", "1")),
                          tmp_path / "out.xml")
    root = ET.parse(copy).getroot()
    (integrator,) = root.iter("integrator")
    assert integrator.get("type") == "direct"
    assert {e.get("name"): e.get("value") for e in integrator} == \
        {"hide_emitters": "true", "emitter_samples": "0", "bsdf_samples": "1"}
    assert [e.get("name") for e in root if e.tag == "default"] == ["integrator", "spp", "res"]
    assert default_strategy(ImageCase("plane_rect_light", "direct"), scene) is None  # the file sets its own


def test_the_cases_own_render_is_mis_where_the_file_sets_nothing():
    assert default_strategy(ImageCase("plane_rect_light", "direct"), SCENES / "plane_rect_light.xml") == "mis"


def test_each_strategy_has_a_seed_of_its_own():
    case = ImageCase("plane_rect_light", "direct")
    seeds = [strategy_seed(7, name, case) for name in ("ems", "mats", "mis")]
    assert len({7, *seeds}) == 4


def test_each_strategy_check_is_one_more_member_of_the_runs_family():
    from harness.images.run import comparison_level, strategy_checks
    from harness.statistics.constants import SIGNIFICANCE, sidak_level

    cases = [ImageCase("plane_rect_light", "direct"), ImageCase("plane_rect_light", "ao"), ImageCase("cornell", "direct")]
    checks = strategy_checks(cases, Reader())
    assert [why is None for why in checks.values()] == [True, False, False]
    assert comparison_level(cases, dict.fromkeys(cases, False), checks) == sidak_level(SIGNIFICANCE, 4)
    assert comparison_level(cases, dict.fromkeys(cases, False), strategy_checks(cases, Reader(reads=False))) == \
        sidak_level(SIGNIFICANCE, 3)
