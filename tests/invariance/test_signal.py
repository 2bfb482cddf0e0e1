"""A base render without signal leaves its cells not judged, and batches that are one image where the estimator
has noise fail them; a noiseless estimator, a constant image of another value and independent batches do not."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from harness.comparison.summary import summarize
from harness.integrators import entry
from harness.invariance.cell import Cell, InvarianceCase
from harness.invariance.signal import NO_SIGNAL, BaseSignal, structure

K, SIZE = 8, 32
HERE = Path(__file__)


def _occlusion(seed: int, spp: int = 32) -> np.ndarray:
    """K batches of a binary estimator whose mean varies across the image (ao-like)."""
    p = np.linspace(0.05, 0.95, SIZE)[None, :, None] * np.ones((SIZE, 1, 3))
    return np.random.default_rng(seed).binomial(spp, p, size=(K, SIZE, SIZE, 3)) / spp


def _signal(batches: np.ndarray) -> BaseSignal:
    return BaseSignal.of(batches, summarize(batches))


def test_an_all_black_base_has_no_signal_and_its_cell_is_not_judged():
    signal = _signal(np.zeros((K, SIZE, SIZE, 3)))
    assert signal.no_signal == NO_SIGNAL and signal.no_signal.startswith("the base render is constant (all 0)")
    assert signal.unused_seed(entry("ao")) is None  # no signal is not a seed that went unused
    cell = Cell("black", "scale", InvarianceCase(HERE, "ao", 32, SIZE), base=signal)
    assert (cell.status, cell.passed, cell.judged, cell.not_judged) == ("inconclusive", False, False, NO_SIGNAL)
    assert cell.to_json()["status"] == "inconclusive"


def test_a_constant_image_of_another_value_is_judged():
    """ao on a lone plane filling the view: rho L everywhere, which every rewrite must keep (or scale)."""
    signal = _signal(np.full((K, SIZE, SIZE, 3), 0.7))
    assert signal.no_signal is None and signal.unused_seed(entry("ao")) is None and signal.varied == 0
    assert Cell("mcval", "scale", InvarianceCase(HERE, "ao", 32, SIZE), base=signal).status == "pass"


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_independent_batches_are_not_accused(seed):
    signal = _signal(_occlusion(seed))
    assert signal.varying == SIZE * SIZE * 3 and signal.unused_seed(entry("ao")) is None


@pytest.mark.parametrize("integrator", ["ao", "simple"])
def test_one_image_repeated_fails_where_the_estimator_has_noise(integrator):
    copies = np.repeat(_occlusion(4)[:1], K, axis=0)
    reason = _signal(copies).unused_seed(entry(integrator))
    assert reason.startswith("batches not independent: all 8 batches of the base render are the same image")
    assert reason.endswith("is the seed it is given used?")
    cell = Cell("seedless", "light", InvarianceCase(HERE, integrator, 32, SIZE), base=_signal(copies),
                dependence=reason)
    assert cell.status == "fail" and not cell.passed


def test_a_noiseless_varying_image_of_normals_is_not_accused_without_a_reference():
    """Normals are constant over each flat surface: an engine sampling pixel centres renders them without noise."""
    two_walls = np.zeros((K, SIZE, SIZE, 3))
    two_walls[:, :, : SIZE // 2, 0], two_walls[:, :, SIZE // 2:, 2] = 1.0, 1.0
    signal = _signal(two_walls)
    assert signal.alike and signal.varied > 0
    assert signal.unused_seed(entry("normals")) is None
    assert signal.unused_seed(entry("ao")) is not None


def test_structure_counts_values_off_their_channel_median():
    image = np.zeros((4, 4, 3))
    image[0, 0] = (1.0, 2.0, 0.0)
    assert structure(image) == 2 and structure(np.full((4, 4, 3), 3.0)) == 0


def test_a_signal_survives_json():
    signal = _signal(_occlusion(5))
    back = BaseSignal.from_json(signal.to_json())
    assert back == signal and back.dependence is None and not back.alike
