"""Mitsuba's mappings of mcval's integrators (harness/engines/mitsuba_integrators.py): normals, simple and ao
as listed; an integrator whose Mitsuba plugin has its name and parameters mapped from its entry alone."""
import dataclasses
import xml.etree.ElementTree as ET

from harness.engines import mitsuba_integrators
from harness.engines.mitsuba_integrators import mitsuba_mapping
from harness.engines.mitsuba_scene import mitsuba_xml
from harness.integrators import entry

SCENE = """<scene version="3.0.0">
  <integrator type="direct"><integer name="emitter_samples" value="4"/><boolean name="hide_emitters" value="false"/></integrator>
  <emitter type="point"/><emitter type="constant"/><emitter type="spot"/>
  <shape type="rectangle"><emitter type="area"/></shape>
  <shape type="rectangle"/><shape type="rectangle"/>
</scene>
"""


def _direct(monkeypatch):
    """An entry such as `direct` would have: Mitsuba's plugin of its name and parameters, area and point lights."""
    direct = dataclasses.replace(entry("simple"), name="direct", emitters=("point", "area"), requirements=(),
                                 parameters=(("integer", "emitter_samples", "1"), ("integer", "bsdf_samples", "1"),
                                             ("boolean", "hide_emitters", "true")))
    monkeypatch.setattr(mitsuba_integrators, "entry", lambda name: direct if name == "direct" else entry(name))


def test_the_suite_integrators_keep_their_plugins():
    assert mitsuba_mapping("normals").summary().startswith("aov(aovs=nn:sh_normal); drops point, constant")
    assert mitsuba_mapping("simple").summary().startswith("direct(emitter_samples=1, bsdf_samples=0); drops constant")
    assert mitsuba_mapping("ao").summary().endswith("adds constant emitter if none; every material white diffuse")


def test_a_new_integrator_of_mitsubas_name_is_mapped_from_its_entry(monkeypatch):
    _direct(monkeypatch)
    mapping = mitsuba_mapping("direct")
    assert mapping.plugin == "direct" and mapping.same_estimator
    assert mapping.drop_emitters == ("constant", "directional", "spot", "projector", "envmap")
    assert not mapping.drop_area_emitters and not mapping.add_environment
    root = ET.fromstring(mitsuba_xml(SCENE, "direct"))
    # The file's own values of its parameters win (its integrator is Mitsuba's direct); the rest are defaults.
    assert {e.get("name"): e.get("value") for e in root.find("integrator")} == \
        {"emitter_samples": "4", "bsdf_samples": "1", "hide_emitters": "false"}
    assert [e.get("type") for e in root.findall("emitter")] == ["point"]
    assert len([e for s in root.iter("shape") for e in s.iter("emitter")]) == 1  # the area light stays


def test_another_estimator_of_an_image_is_rendered_as_that_image_but_never_alike(tmp_path, monkeypatch):
    uniform = dataclasses.replace(entry("ao"), name="ao_uniform", same_image_as="ao")
    monkeypatch.setattr(mitsuba_integrators, "entry", lambda name: uniform if name == "ao_uniform" else entry(name))
    scene = tmp_path / "scene.xml"
    scene.write_text(SCENE)
    assert mitsuba_mapping("ao_uniform").plugin == "direct"
    assert mitsuba_mapping("ao").draws_same_estimator(scene)
    assert not mitsuba_mapping("ao_uniform").draws_same_estimator(scene)


def test_an_aov_entry_is_mitsubas_aov_plugin(monkeypatch):
    albedo = dataclasses.replace(entry("normals"), name="albedo", aov="albedo")
    monkeypatch.setattr(mitsuba_integrators, "entry", lambda name: albedo if name == "albedo" else entry(name))
    assert mitsuba_mapping("albedo").properties == (("string", "aovs", "albedo:albedo"),)
