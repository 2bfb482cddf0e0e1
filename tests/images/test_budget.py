"""A budget from a target (--detect-bias): the samples per pixel it chooses find the target bias as often as
stated, a target the reference's own noise hides is refused with that reason, and bad values are refused."""
import pytest

from harness.cli import main
from harness.comparison.compare import compare_summaries
from harness.comparison.summary import summarize
from harness.engines.registry import make_engine
from harness.images.budget import parse_bias, plan_budget
from harness.images.references import load_reference, render_params
from harness.images.suite import select_cases

ALPHA = 0.01  # the per-comparison level of a run of cornell:ao alone


@pytest.fixture(scope="module")
def cornell_ao():
    (case,) = select_cases(["cornell:ao"])
    return case, make_engine("mcval"), make_engine("mitsuba")


@pytest.mark.slow
def test_a_one_percent_bias_is_found_about_90_percent_of_the_time(cornell_ao):
    case, mcval, mitsuba = cornell_ao
    # The pilot (the case's 32 spp) already finds 0.48 %: the budget for 1 % lies below it, planned from its noise.
    budget = plan_budget(case, mcval, mitsuba, 0.01, ALPHA, seed=12345)
    assert budget.spp is not None and budget.spp < budget.pilot_spp and budget.planned_bias <= 0.01 < budget.pilot_bias * 4
    reference, _ = load_reference(case, mitsuba)
    found, runs = 0, 60
    for i in range(runs):
        batches = mcval.render(str(case.path), "ao", budget.spp, budget.batches, 60_000 + i, render_params(case)).batches
        c = compare_summaries(summarize(batches * 1.01), reference.summary, ALPHA, samples=(budget.spp, reference.spp),
                              metrics=False, power=False, same_estimator=True)
        found += not c.scales[2].passed  # the image scale: the bias the budget is for
    # 90 % of 60: 54, within 2.2 binomial standard deviations (2.3 each).
    assert 49 <= found <= 59, found


def test_a_target_below_the_references_noise_is_refused_with_the_reason(cornell_ao):
    case, mcval, mitsuba = cornell_ao
    budget = plan_budget(case, mcval, mitsuba, 1e-6, ALPHA, seed=1)
    assert budget.spp is None and "the reference's own noise" in budget.reason and budget.line.startswith("cornell:ao")


def test_bias_values_are_read_as_percentages_or_fractions():
    assert parse_bias("0.5%") == pytest.approx(0.005) and parse_bias("0.02") == 0.02
    for bad in ("0", "150%", "-1%", "half"):
        with pytest.raises(ValueError):
            parse_bias(bad)


def test_the_option_refuses_a_bad_value(capsys):
    with pytest.raises(SystemExit):
        main(["images", "--detect-bias", "200%"])
    assert "--detect-bias" in capsys.readouterr().err
