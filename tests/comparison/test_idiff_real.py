"""Why this harness exists, on real renders: idiff (OpenImageIO's image diff at its own test suite's
thresholds) fails a correct-but-noisy render and passes a 2 % bias, and our statistical test does the
opposite in both cases. Both use the stored Mitsuba references and the thresholds the report uses."""
from pathlib import Path

import pytest

from harness.engines.mitsuba import MitsubaEngine
from harness.engines.mcval import McvalEngine
from harness.comparison.compare import compare_summaries
from harness.comparison.summary import summarize
from harness.comparison.idiff import idiff
from harness.images.references import load_reference
from harness.images.run import case_seed, run_images
from harness.images.suite import TESTED_SPP, ImageCase
from harness.invariance.rewrite import rewrite
from harness.statistics.constants import IMAGE_BATCHES


@pytest.fixture(scope="module")
def engines():
    return McvalEngine(), MitsubaEngine()


def test_noisy_but_correct_cornell_box_ao_fails_idiff_and_passes_mcval(engines):
    """Mitsuba's own Cornell box under ao at the validation budget (32 spp x 8 batches) against the stored
    reference: about half the pixels differ by more than 0.004 (Monte Carlo noise, no bias: the image
    means agree to 2e-4), so idiff fails; our test, which knows the noise, passes."""
    mcval, mitsuba = engines
    (result,), _ = run_images([ImageCase("cornell_box", "ao", group="real")], mcval, mitsuba, seed=0)
    assert result.passed, result.comparisons["mitsuba"].failed_scales
    assert result.idiff["verdict"] == "FAIL"
    assert result.idiff["fail_percent_of_pixels"] > 10


def test_two_percent_bias_passes_idiff_and_fails_mcval(engines, tmp_path):
    """plane_point under simple, with our floor's reflectance 2 % too high (0.51 for 0.5). The image's
    largest value is 0.199, so no pixel moves by more than 0.00398, under idiff's 0.004: idiff passes.
    Our test rejects it at every scale (the unbiased render passes: checked first)."""
    mcval, mitsuba = engines
    case = ImageCase("plane_point", "simple")
    reference, _ = load_reference(case, mitsuba)
    assert reference is not None

    def compare(scene: Path):
        mine = mcval.render(str(scene), case.integrator, TESTED_SPP[case.integrator], IMAGE_BATCHES, case_seed(case, 0))
        comparison = compare_summaries(summarize(mine.batches), reference.summary, samples=(mine.spp, reference.spp))
        return comparison, idiff(mine.batches.mean(axis=0), reference.summary.mean_image)

    fair, fair_idiff = compare(case.path)
    assert fair.passed and fair_idiff["verdict"] == "PASS"
    biased, biased_idiff = compare(rewrite(case.path, tmp_path / case.path.name, "reflectance", 1.02))
    assert biased_idiff["verdict"] == "PASS" and biased_idiff["maxerror"] < 0.004
    assert not biased.passed
    assert set(biased.failed_scales) == {"pixel", "tile", "image"}
