"""The benchmark measures error against the closed form where one exists, not against a reference that
breaks it: at the 1e-3 scale the simple image of the sphere on a floor by Mitsuba as shipped is biased (a
finding), so against it our correct render's error stalls at that bias; against the closed form it is noise."""
import pytest

from harness.bench.ladder import relmse
from harness.bench.truth import bench_truth
from harness.engines.mitsuba import MitsubaEngine
from harness.engines.mcval import McvalEngine
from harness.images.references import RESOLUTION, load_reference, render_reference
from harness.images.suite import ImageCase


@pytest.fixture(scope="module")
def mitsuba():
    return MitsubaEngine()


@pytest.fixture(scope="module")
def mitsuba_native():
    return MitsubaEngine(native=True)


def _errors(case: ImageCase, mitsuba) -> tuple[float, float]:
    """Our 64-spp render's relMSE against the bench's truth and against the Mitsuba reference."""
    truth, label = bench_truth(case, mitsuba, spp=16)
    assert label.startswith("closed form")
    stored = load_reference(case, mitsuba)[0] or render_reference(case, mitsuba)
    image = McvalEngine().render(str(case.path), case.integrator, 64, 1, 5, {"res": str(RESOLUTION)}).batches[0]
    return relmse(image, truth), relmse(image, stored)


@pytest.mark.slow
def test_a_closed_form_case_is_measured_against_the_closed_form(mitsuba_native, mitsuba):
    # Against native Mitsuba's biased reference at 1e-3 our error is mostly that bias (measured: 40 times the
    # noise of 64 samples); against the closed form it is that noise.
    against_truth, against_mitsuba = _errors(ImageCase("sphere_floor_milli", "simple"), mitsuba_native)
    assert against_truth < against_mitsuba / 3, (against_truth, against_mitsuba)
    # The twins: the stored reference (its offset scales with the scene) holds the closed form at 1e-3, as
    # Mitsuba as shipped does at unit scale: both errors are the same noise.
    against_truth, against_mitsuba = _errors(ImageCase("sphere_floor_milli", "simple"), mitsuba)
    assert 0.7 < against_truth / against_mitsuba < 1.4, (against_truth, against_mitsuba)
    against_truth, against_mitsuba = _errors(ImageCase("sphere_floor_unit", "simple"), mitsuba_native)
    assert 0.7 < against_truth / against_mitsuba < 1.4, (against_truth, against_mitsuba)


def test_a_case_without_a_closed_form_is_measured_against_the_stored_reference(mitsuba):
    truth, label = bench_truth(ImageCase("cornell", "simple"), mitsuba, spp=16)
    assert "stored reference" in label and "mitsuba" in label.lower()
    assert truth.spp > 16
