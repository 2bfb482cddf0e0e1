"""A null comparison judges what the suite judges: against a closed form that knows the image's mean only
(direct's), the tested engine's noise is not compared, so a correct renderer is not rejected for it; its mean
still is."""
import pytest

from harness.engines.mcval import McvalEngine
from harness.images.null_task import NullJob, null_comparison
from harness.images.suite import ImageCase
from harness.statistics.calibration_rates import CALIBRATION_LEVELS
from tests.helpers.scaled_engine import Scaled


def _job(engine, seed: int) -> NullJob:
    return NullJob("test-closed-form", ImageCase("plane_rect_light", "direct"), seed, 32, 1e-3, engine, engine)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_direct_against_its_closed_form_is_not_judged_on_its_noise(seed):
    rejected = null_comparison(_job(McvalEngine(), seed))["rejected"]
    assert not rejected[str(min(CALIBRATION_LEVELS))]["whole"], rejected


def test_a_biased_direct_is_still_rejected_by_its_closed_form():
    rejected = null_comparison(_job(Scaled(1.2), 0))["rejected"]
    assert rejected[str(max(CALIBRATION_LEVELS))]["image"], rejected


def test_the_variance_against_another_estimator_is_no_rejection():
    rejected = null_comparison(_job(McvalEngine(), 0))["rejected"]
    assert not any(r["variance"] for r in rejected.values()), rejected
