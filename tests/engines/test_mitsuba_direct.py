"""mcval_direct is Mitsuba's `direct` with another ray offset: given Mitsuba's offset it renders Mitsuba's
image; with its own it lights a floor that Mitsuba's offset puts in shadow."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from harness.engines import mitsuba_direct

SCENES = Path(__file__).resolve().parents[2] / "scenes"

pytestmark = pytest.mark.mitsuba

#: Mitsuba's own offset, (1 + max|p|) * 1500 float epsilons, in mcval_direct's terms.
MITSUBA_OFFSET = {"offset_epsilons": 1500.0, "offset_floor": 1.0}
#: The height of the slot between the floor and its cover: below Mitsuba's offset, far above mcval's.
GAP = 5e-5


@pytest.fixture(scope="module")
def mi(mitsuba):
    mi = mitsuba._activate()
    mitsuba_direct.register(mi)
    return mi


def _scene(mi, integrator: dict, light: bool = True, gap: float = GAP, light_z: float = GAP / 2):
    """A floor (z = 0, x and y in [-1, 1]) seen from above, under a cover (x in [0, 1]) `gap` above it, a
    point light at height `light_z` (by default in the slot between them; else a constant emitter), and a
    ceiling above the camera, which a shadow ray running past its light would hit."""
    emitter = {"type": "point", "position": [0.5, 0, light_z], "intensity": {"type": "rgb", "value": 1e4 if light_z < 1 else 10}} \
        if light else {"type": "constant"}
    return mi.load_dict({
        "type": "scene", "integrator": integrator, "light": emitter,
        "floor": {"type": "rectangle"},
        "cover": {"type": "rectangle",
                  "to_world": mi.ScalarTransform4f().translate([0.5, 0, gap]).scale([0.5, 1, 1])},
        "ceiling": {"type": "rectangle", "to_world": mi.ScalarTransform4f().translate([0, 0, 2.5]).scale(3)},
        "sensor": {"type": "perspective", "fov": 60,
                   "to_world": mi.ScalarTransform4f().look_at([0, 0, 2.3], [0, 0, 0], [0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": 24, "height": 24, "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent", "sample_count": 16}}})


def _render(mi, scene) -> np.ndarray:
    return np.array(mi.render(scene, seed=3), dtype=np.float64)[..., :3]


@pytest.mark.parametrize("light", [True, False], ids=["point light", "environment"])
def test_with_mitsubas_offset_it_renders_mitsubas_image(mi, light):
    props = {"emitter_samples": 1, "bsdf_samples": 0} if light else {"hide_emitters": True}
    native = _render(mi, _scene(mi, {"type": "direct", **props}, light, gap=0.5, light_z=2))
    rebuilt = _render(mi, _scene(mi, {"type": mitsuba_direct.PLUGIN, **props, **MITSUBA_OFFSET}, light, gap=0.5,
                                 light_z=2))
    assert native.max() > 0.05 and (native == 0).any()  # lit, and shadowed where the cover hides the light
    np.testing.assert_allclose(rebuilt, native, atol=1e-5 * native.max())


def test_its_own_offset_lights_a_floor_that_mitsubas_shadows(mi):
    """A shadow ray from the floor beside the slot rises to the light and never reaches the cover. Mitsuba's
    starts 1e-4 to 2e-4 up, above the cover, and comes down onto it: the floor is black. mcval_direct's starts
    ~6e-6 up, inside the slot, as the limit at the surface does: the floor is lit."""
    props = {"emitter_samples": 1, "bsdf_samples": 0}
    native = _render(mi, _scene(mi, {"type": "direct", **props}))
    tight = _render(mi, _scene(mi, {"type": mitsuba_direct.PLUGIN, **props}))
    beside = tight[6:18, 6:12]  # the pixels over the floor beside the slot (x in [-0.9, 0])
    assert beside.min() > 5e-3
    assert (native == 0).all()


def test_the_reference_renders_with_it_and_mitsuba_native_as_shipped():
    import xml.etree.ElementTree as ET

    from harness.engines.mitsuba_scene import mitsuba_xml
    from harness.engines.registry import make_engine

    text = (SCENES / "plane_point.xml").read_text()
    for integrator in ("simple", "ao"):
        assert ET.fromstring(mitsuba_xml(text, integrator, tight=True)).find("integrator").get("type") == \
            mitsuba_direct.PLUGIN
        assert ET.fromstring(mitsuba_xml(text, integrator)).find("integrator").get("type") == "direct"
    reference, native = make_engine("mitsuba"), make_engine("mitsuba-native")
    assert not reference.native and native.native and native.name == "mitsuba-native"
    # The version is the stored references' provenance: a reference of the other kind is never reused.
    assert mitsuba_direct.PLUGIN in reference.version() and mitsuba_direct.PLUGIN not in native.version()
