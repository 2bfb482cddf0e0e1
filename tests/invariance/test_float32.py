"""Breaks float32 explains: judged from the rewritten scene file, never from the engine's word."""
from __future__ import annotations

import contextlib
from pathlib import Path

import pytest

from harness.engines.base import Engine, RenderFailed, RenderResult
from harness.invariance.check import InvarianceCase, run_invariances
from harness.invariance.findings import invariance_payload
from harness.invariance.float32 import float32_limit
from harness.invariance.rewrite import rewrite
from harness.invariance.variants import TRANSLATION, invariance

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def test_a_millimetre_sphere_moved_tens_of_units_is_beyond_float32(tmp_path):
    moved = rewrite(SCENES / "sphere_floor_milli.xml", tmp_path / "m.xml", "translate", TRANSLATION)
    why = float32_limit(moved)
    assert why and "radius 0.001" in why and "largest coordinate 30" in why and "starts once the centre is 10" in why


def test_representable_rewrites_have_no_float32_limit(tmp_path):
    for scene, kind, value in (("sphere_floor_unit", "translate", TRANSLATION),
                               ("sphere_floor_milli", "scale", 1e-3),  # radius 1e-6 at the origin: fine
                               ("sphere_floor_kilo", "scale", 1e3),
                               ("cornell", "translate", TRANSLATION)):
        assert float32_limit(rewrite(SCENES / f"{scene}.xml", tmp_path / f"{scene}.xml", kind, value)) is None


def test_a_small_disk_or_cylinder_moved_far_is_beyond_float32_as_our_loader_says(tmp_path, mcval):
    """The same limit as our loader's (renderer/disk_cylinder_loader.cpp), read from the file: a 1e-3 disk
    or cylinder at 30 from the origin is beyond it, one of size 1 is not."""
    for shape in ('<shape type="disk"><transform name="to_world"><scale value="1e-3, 2e-3, 1"/>'
                  '<translate value="TX, 0, 0"/></transform></shape>',
                  '<shape type="cylinder"><point name="p0" value="TX, 0, 0"/><point name="p1" value="TX, 0, 1e-3"/>'
                  '<float name="radius" value="0.5"/></shape>'):
        for tx, beyond in (("30", True), ("3", False)):
            scene = tmp_path / "shape.xml"
            scene.write_text('<scene version="3.0.0"><sensor type="orthographic"><film type="hdrfilm">'
                             '<integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>'
                             + shape.replace("TX", tx) + "</scene>")
            why = float32_limit(scene)
            assert bool(why) == beyond, (shape, tx, why)
            if beyond:
                assert "largest coordinate 30" in why and "size 0.001" in why
            with pytest.raises(RenderFailed) if beyond else contextlib.nullcontext():
                mcval.render(str(scene), "normals", 1, 1, 0)


class RefusesTranslations(Engine):
    """Our renderer, but it refuses every translated scene as if float32 could not hold it."""

    name = "refuser"

    def __init__(self) -> None:
        from harness.engines.mcval import McvalEngine
        self._mcval = McvalEngine()

    def version(self) -> str:
        return "mcval, refusing translations"

    def render(self, scene, integrator, spp, batches, seed, params=None) -> RenderResult:
        if ".translate." in Path(scene).name:
            raise RenderFailed("error: float32 could not place points on it")
        return self._mcval.render(scene, integrator, spp, batches, seed, params)


def test_the_milli_sphere_translation_is_float32_but_a_refused_representable_scene_fails():
    from harness.engines.mcval import McvalEngine

    cases = [InvarianceCase(SCENES / "sphere_floor_milli.xml", "ao", 8, 24),
             InvarianceCase(SCENES / "plane_point.xml", "simple", 8, 24)]
    cells, _ = run_invariances([McvalEngine(), RefusesTranslations()], cases, [invariance("translate")], seed=1)
    found = {(c.engine, c.case.key): c for c in cells}
    milli = found["mcval", "sphere_floor_milli:ao"]
    assert milli.passed and milli.status == "float32" and milli.beyond_float32[0].error  # our loader refuses it
    assert found["mcval", "plane_point:simple"].status == "pass"
    assert found["refuser", "sphere_floor_milli:ao"].status == "float32"
    assert found["refuser", "plane_point:simple"].status == "fail"  # its refusal is not float32's limit
    payload = invariance_payload(cells, 1e-3, "mcval", {})
    assert payload["pass"] and len(payload["float32_limits"]) == 2
    assert payload["float32_limits"][0].startswith("mcval sphere_floor_milli:ao translate")
    assert "stops being representable" in payload["translation_reach"]
    assert not invariance_payload(cells, 1e-3, "refuser", {})["pass"]
