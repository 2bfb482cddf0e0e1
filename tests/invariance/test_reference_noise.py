"""Base batches that are one image fail against a Mitsuba reference whose base of the same case, drawing the
same estimator, varies; not where the reference is as noiseless, nor where its estimator is another, nor where
the engine says it draws an estimator of its own."""
from __future__ import annotations

import numpy as np

from harness.comparison.summary import summarize
from harness.engines.base import Engine
from harness.engines.mitsuba_integrators import mitsuba_mapping
from harness.images.suite import SCENES_DIR
from harness.invariance.cell import Cell, InvarianceCase
from harness.invariance.reference_noise import judge_against_references
from harness.invariance.signal import BaseSignal

K, SIZE = 8, 32


class _Named(Engine):
    """An engine by name that renders nothing; "mitsuba" says what Mitsuba's mappings say of the estimator."""

    def __init__(self, name: str) -> None:
        self.name = name

    def version(self) -> str:
        return self.name

    def draws_same_estimator(self, scene, integrator) -> bool:
        return self.name == "mitsuba" and mitsuba_mapping(integrator).draws_same_estimator(scene)

    def draws_integrator_estimator(self, integrator: str) -> bool:
        return not self.name.startswith("own-")


def _judge(cells: list[Cell]) -> None:
    judge_against_references(cells, [_Named(name) for name in {c.engine for c in cells}])


def _walls(seed: int | None) -> np.ndarray:
    """Normals of two walls, noisy along their edge (seed), or one image repeated (None)."""
    image = np.zeros((K, SIZE, SIZE, 3))
    image[:, :, : SIZE // 2, 0], image[:, :, SIZE // 2:, 2] = 1.0, 1.0
    if seed is not None:
        image[:, :, SIZE // 2 - 1 : SIZE // 2 + 1] = np.random.default_rng(seed).random((K, SIZE, 2, 3))
    return image


def _cell(engine: str, batches: np.ndarray, scene: str = "cornell", integrator: str = "normals") -> Cell:
    case = InvarianceCase(SCENES_DIR / f"{scene}.xml", integrator, 16, SIZE)
    return Cell(engine, "rotate", case, base=BaseSignal.of(batches, summarize(batches)))


def test_one_image_where_mitsuba_varies_is_a_seed_not_used():
    tested, reference = _cell("seedless", _walls(None)), _cell("mitsuba", _walls(1))
    _judge([tested, reference])
    assert tested.dependence.startswith("batches not independent: all 8 batches of the base render are the same "
                                        "image, where mitsuba's, drawing the same estimator, vary at")
    assert tested.status == "fail" and reference.dependence is None


def test_independent_batches_and_a_noiseless_reference_pass():
    tested = _cell("mcval", _walls(2))
    _judge([tested, _cell("mitsuba", _walls(3))])
    assert tested.dependence is None
    noiseless = _cell("analytic", _walls(None))
    _judge([noiseless, _cell("mitsuba", _walls(None))])
    assert noiseless.dependence is None and noiseless.status == "pass"


def test_where_mitsuba_draws_another_estimator_its_noise_is_no_evidence(tmp_path):
    """simple with several point lights: Mitsuba's one emitter sample picks one, mcval sums them all."""
    (tmp_path / "two_lights.xml").write_text('<scene version="3.0.0"><emitter type="point"/><emitter type="point"/>'
                                             "</scene>\n")
    case = InvarianceCase(tmp_path / "two_lights.xml", "simple", 32, SIZE)
    tested, reference = _cell("seedless", _walls(None), integrator="simple"), _cell("mitsuba", _walls(4))
    tested.case = reference.case = case
    _judge([tested, reference])
    assert tested.dependence is None


def test_an_engine_drawing_its_own_estimator_may_be_noiseless():
    """An engine file's other_estimators: its estimator may have no noise where Mitsuba's has (an irradiance it
    computes exactly); the seedless engine of the first test, declared so, is not judged."""
    tested, reference = _cell("own-exact", _walls(None)), _cell("mitsuba", _walls(1))
    _judge([tested, reference])
    assert tested.dependence is None and reference.dependence is None
