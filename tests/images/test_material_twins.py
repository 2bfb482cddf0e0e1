"""Scattering BSDFs through the image suite (scenes/materials.xml: mirror, glass, plastic and their rough kinds):
our direct and path pass against Mitsuba's stored references, and a renderer that reads one material wrong fails.
The wrong readings are planted by handing our renderer a scene with that material changed, as a loader with the
defect would see it:
- a dielectric's index not found and taken as vacuum's (1), where Mitsuba's default is bk7 (1.5046);
- a plastic's RGB diffuse reflectance read in the wrong channel order;
- a conductor's specular_reflectance ignored (taken as 1).
Each case at the suite's 128 x 128 and its integrator's samples, seed 0. What they cannot see: glass of water's
index (1.33) for bk7 moves 441 pixels by more than 10 % and the image mean by 0.2 %, under path's noise there at
128 samples per pixel (its verdict is PASS)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from harness.engines.mcval import McvalEngine
from harness.images.run import run_images
from harness.images.suite import select_cases

SCENE = "materials"
#: (pattern, replacement): a pattern matches the scene file and the copies the harness writes of it (the strategy
#: check's, whose elements are written again: `<bsdf ... />`).
DEFECTS = {
    "default_ior": (r'<bsdf type="dielectric"\s*/>',
                    '<bsdf type="dielectric"><float name="int_ior" value="1"/></bsdf>'),
    "channel_order": ('value="0.1, 0.27, 0.36"', 'value="0.36, 0.27, 0.1"'),
    "specular_ignored": (r'<rgb name="specular_reflectance" value="0.9, 0.7, 0.5"\s*/>', ""),
}


class MisreadingEngine(McvalEngine):
    """Our renderer given the scene with the pattern `old` replaced by `new` (a copy in `copies`, never beside the
    scene)."""

    def __init__(self, old: str, new: str, copies: Path) -> None:
        super().__init__()
        self.old, self.new, self.copies = old, new, Path(copies)

    def __reduce__(self):
        return MisreadingEngine, (self.old, self.new, self.copies)

    def render(self, scene, integrator, spp, batches, seed, params=None):
        text, count = re.subn(self.old, self.new, Path(scene).read_text())
        assert count == 1, f"the planted defect no longer matches {scene}"
        copy = self.copies / Path(scene).name
        copy.write_text(text)
        return super().render(str(copy), integrator, spp, batches, seed, params)


@pytest.fixture(scope="module")
def cases():
    return {c.integrator: c for c in select_cases([f"{SCENE}:direct", f"{SCENE}:path"])}


@pytest.mark.parametrize("integrator", ["direct", "path"])
def test_our_renderer_passes_on_every_material(cases, mitsuba, integrator):
    (result,), _ = run_images([cases[integrator]], McvalEngine(), mitsuba)
    assert result.verdict == "PASS", result.why


@pytest.mark.parametrize("defect", sorted(DEFECTS))
def test_a_material_read_wrong_fails_against_mitsuba(cases, mitsuba, tmp_path, defect):
    (result,), _ = run_images([cases["path"]], MisreadingEngine(*DEFECTS[defect], tmp_path), mitsuba)
    assert result.verdict == "FAIL"
    assert not result.comparisons["mitsuba"].passed
