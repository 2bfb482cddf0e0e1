"""Why a selection holds no image case, and what a run's cases judged."""
from dataclasses import dataclass

from harness.images.judged import image_tally, why_no_cases
from harness.images.suite import ImageCase


def test_why_no_cases_names_the_integrators_or_the_scenes():
    assert why_no_cases("theirs", (), []).startswith("the engine theirs renders none of the integrators the suite "
                                                    "has an entry for, ")
    cases = [(ImageCase(f"s{i}", "simple"), "no point light") for i in range(5)]
    assert why_no_cases("theirs", ("simple",), cases) == (
        "no case of the engine theirs (it renders simple) applies to the scenes: s0:simple: no point light, "
        "s1:simple: no point light, s2:simple: no point light and 2 more")


@dataclass
class _Result:
    case: ImageCase
    verdict: str


def test_a_tally_counts_passes_and_failures_and_why_others_were_not_judged():
    results = [_Result(ImageCase("a", "ao"), "PASS"), _Result(ImageCase("b", "ao"), "FAIL"),
               _Result(ImageCase("d", "ao"), "INCONCLUSIVE")]
    tally = image_tally(results, [(ImageCase("c", "simple"), "no point light")])
    assert (tally.passed, tally.failed) == (1, 1)
    assert tally.not_judged == ("1 inconclusive (d:ao)", "1 not applicable (c:simple: no point light)")
    assert image_tally([], [], "no scene was selected").not_judged == ("no scene was selected",)
