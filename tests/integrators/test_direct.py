"""direct's entry: what a scene needs for its case."""
import xml.etree.ElementTree as ET

from harness.integrators import entry


def unmet(scene: str) -> list[str]:
    root = ET.fromstring(scene)
    return [why for _, check in entry("direct").requirements if (why := check(root))]


def test_a_scene_without_an_emitter_is_not_applicable():
    assert unmet('<scene version="3.0.0"><shape type="rectangle"/></scene>') == ["no emitter"]


def test_an_emitter_it_does_not_model_is_no_missing_light():
    # Mitsuba's projector scenes: the case runs, and the engine that models no projector refuses it by name.
    assert unmet('<scene version="3.0.0"><emitter type="projector"/></scene>') == []
    assert unmet('<scene version="3.0.0"><shape type="obj"><emitter type="area"/></shape></scene>') == []


def test_a_projector_is_a_delta_light_for_the_strategy_check():
    strategies = entry("direct").strategies
    assert strategies.applies(ET.fromstring('<scene><emitter type="projector"/></scene>')) is not None
    assert strategies.applies(ET.fromstring('<scene><shape type="obj"><emitter type="area"/></shape></scene>')) is None


def test_a_delta_lobe_keeps_directs_strategies_apart_but_not_paths():
    """Through a mirror or glass only a BSDF sample finds the light: direct's emitter samples alone see it black.
    path's "ems" counts the emission found after a delta lobe, so its strategies still estimate one image."""
    lit = '<shape type="obj"><emitter type="area"/></shape>'
    for bsdf, apart in (("conductor", True), ("dielectric", True), ("plastic", True), ("roughconductor", False),
                        ("roughdielectric", False), ("diffuse", False)):
        root = ET.fromstring(f'<scene>{lit}<shape type="sphere"><bsdf type="{bsdf}"/></shape></scene>')
        assert (entry("direct").strategies.applies(root) is not None) == apart, bsdf
        assert entry("path").strategies.applies(root) is None, bsdf
