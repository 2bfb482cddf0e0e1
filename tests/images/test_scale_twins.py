"""Scale twins (harness/images/scale_twins.py): the pairs are the scenes make_sphere_floor.py writes at each
scale, and the reference engine's render of the twin overrules a reference that breaks at its own scale, while a
tested image that breaks with it still fails."""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest

from harness.comparison.summary import summarize
from harness.engines.base import RenderResult
from harness.images.evaluate import evaluate
from harness.images.references import Reference
from harness.images.scale_twins import SCALE_TWIN, TWINS, twin_case, twin_label
from harness.images.suite import SCENES_DIR, ImageCase

CASE = ImageCase("sphere_floor_milli", "direct")
SPP, K, SIZE = 64, 8, 32


def _generator():
    spec = importlib.util.spec_from_file_location("make_sphere_floor", SCENES_DIR / "make_sphere_floor.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_twins_are_the_scales_the_generator_writes():
    scales = _generator().SCALES
    assert scales["unit"] == 1.0
    assert TWINS == {f"sphere_floor_{name}": "sphere_floor_unit" for name in scales if name != "unit"}
    assert all((SCENES_DIR / f"{scene}.xml").is_file() for pair in TWINS.items() for scene in pair)


def test_a_twin_case_keeps_the_integrator_and_a_users_scene_has_none():
    twin = twin_case(CASE)
    assert (twin.scene, twin.integrator, twin.group) == ("sphere_floor_unit", "direct", "synthetic")
    assert twin_case(ImageCase("sphere_floor_unit", "direct")) is None
    assert twin_case(ImageCase("sphere_floor_milli", "direct", group="user")) is None
    assert twin_label(CASE, "mitsuba") == "mitsuba at unit scale"


def _batches(seed: int, dark: float = 1.0) -> np.ndarray:
    """K batches of a lit grey image, its lower quarter times `dark` (where a contact point would be)."""
    rng = np.random.default_rng(seed)
    hits = rng.binomial(SPP, 0.6, size=(K, SIZE, SIZE, 1)) / SPP
    image = np.repeat(hits, 3, axis=-1)
    image[:, 3 * SIZE // 4:] *= dark
    return image.astype(np.float32)


def _judge(tested: np.ndarray, reference: np.ndarray, twin: np.ndarray):
    result = RenderResult("mcval", CASE.scene, CASE.integrator, SPP, 1, tested, {"total": 1.0})
    refs = {"mitsuba": Reference(summarize(reference), SPP, {"total": 2.0}, "stored reference"),
            "mitsuba at unit scale": Reference(summarize(twin), SPP, {"total": 2.0}, SCALE_TWIN)}
    return evaluate(CASE, result, refs, alpha=0.01, reference="mitsuba", reference_draws_estimator=True)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_reference_darker_at_its_scale_is_overruled_by_its_own_twin(seed):
    judged = _judge(_batches(seed), _batches(seed + 10, dark=0.95), _batches(seed + 20))
    assert not judged.comparisons["mitsuba"].passed and judged.comparisons["mitsuba at unit scale"].passed
    assert judged.passed and judged.finding is not None and judged.finding.overruled == "mitsuba"
    assert judged.finding.text.startswith("reference breaks its own render of the scale twin")


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_tested_image_darker_with_the_reference_still_fails(seed):
    # Both engines break alike at this scale: only the twin sees it, and the case fails on it.
    judged = _judge(_batches(seed, dark=0.95), _batches(seed + 10, dark=0.95), _batches(seed + 20))
    assert judged.failed and judged.finding is None
    assert judged.comparisons["mitsuba"].passed and not judged.comparisons["mitsuba at unit scale"].passed


def test_a_right_pair_passes_with_no_finding():
    judged = _judge(_batches(1), _batches(11), _batches(21))
    assert judged.passed and judged.finding is None
