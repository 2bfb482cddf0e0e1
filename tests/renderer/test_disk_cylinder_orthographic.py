"""<shape type="disk">, <shape type="cylinder"> and <sensor type="orthographic">: our renderer agrees with
Mitsuba 3 on scenes of our own (tests/renderer/scenes) under every integrator, and a planted wrong value (a
flipped normal, a view scaled by 4 %, an unevenly stretched disk made round) is caught by `normals`."""
from pathlib import Path

import pytest

from harness.comparison.compare import compare_batches

SCENES = Path(__file__).resolve().parent / "scenes"
DISK_CYLINDER, ORTHOGRAPHIC = SCENES / "disk_cylinder.xml", SCENES / "orthographic.xml"
K, SPP = 6, 8
#: Samples per pixel of the other integrators' batches: enough for their noise to hide no bias here.
NOISY = {"simple": 16, "ao": 32}


@pytest.fixture(scope="module")
def references(mitsuba):
    return {scene: mitsuba.render(str(scene), "normals", SPP, K, 101).batches
            for scene in (DISK_CYLINDER, ORTHOGRAPHIC)}


def _mcval(mcval, scene, params=None, seed=1):
    return mcval.render(str(scene), "normals", SPP, K, seed, params or {}).batches


@pytest.mark.parametrize("integrator", sorted(NOISY))
@pytest.mark.parametrize("scene", [DISK_CYLINDER, ORTHOGRAPHIC], ids=lambda p: p.stem)
def test_simple_and_ao_agree_with_mitsuba(mcval, mitsuba, scene, integrator):
    spp = NOISY[integrator]
    test = mcval.render(str(scene), integrator, spp, 8, 1).batches
    reference = mitsuba.render(str(scene), integrator, spp, 8, 101).batches
    assert test.mean() > 0.01
    assert compare_batches(test, reference).passed


def _variant(tmp_path, scene: Path, old: str, new: str) -> Path:
    text = scene.read_text()
    assert text.count(old) == 1, old
    path = tmp_path / scene.name
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("scene", [DISK_CYLINDER, ORTHOGRAPHIC], ids=lambda p: p.stem)
def test_mcval_agrees_with_mitsuba(mcval, references, scene):
    mcval_batches = _mcval(mcval, scene)
    assert (mcval_batches != 0).any(axis=-1).mean() > 0.3  # the shapes fill a good part of the view
    assert compare_batches(mcval_batches, references[scene], signed=True).passed


def test_a_cylinder_with_its_normals_flipped_fails(mcval, references, tmp_path):
    flipped = _variant(tmp_path, DISK_CYLINDER, '<float name="radius" value="0.45"/>',
                       '<float name="radius" value="0.45"/><boolean name="flip_normals" value="true"/>')
    assert not compare_batches(_mcval(mcval, flipped), references[DISK_CYLINDER], signed=True).passed


def test_a_round_disk_for_a_stretched_one_fails(mcval, references, tmp_path):
    round_disk = _variant(tmp_path, DISK_CYLINDER, '<scale value="3, 2, 1"/>', '<scale value="3, 3, 1"/>')
    assert not compare_batches(_mcval(mcval, round_disk), references[DISK_CYLINDER], signed=True).passed


def test_an_orthographic_view_scaled_by_4_percent_fails(mcval, references):
    scaled = _mcval(mcval, ORTHOGRAPHIC, {"scale": "2.6"})
    assert not compare_batches(scaled, references[ORTHOGRAPHIC], signed=True).passed
