"""The strategy check: three unbiased estimators of direct lighting agree; a biased one is named; patterns that
name no single strategy say so; a correct renderer is called anything but "agree" at most at the stated level."""
from types import SimpleNamespace

import numpy as np
import pytest

from harness.comparison.strategies import (STRATEGIES, StrategyPair, block_side, compare_strategies,
                                          read_pattern)
from harness.engines.base import RenderResult
from harness.statistics.calibration_rates import rates
from tools.strategy_triples import AREA_MEASURE, DOUBLE_COUNT, HITS, UNIFORM, null_triple, planted

SPP = 32


def _triple(seed: int, size: int = 32) -> dict[str, np.ndarray]:
    return null_triple(np.random.default_rng(seed), size, spp=SPP)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_three_unbiased_strategies_agree(seed):
    check = compare_strategies(_triple(seed), spp=SPP)
    assert check.verdict == "AGREE" and check.odd is None and not check.disagree
    assert check.reason == "ems, mats and mis agree (3 comparisons at 0.00334 each, 0.01 together)"
    assert [p.names for p in check.pairs] == [("ems", "mats"), ("ems", "mis"), ("mats", "mis")]


# A light pdf left in area measure (a factor over the image), a BSDF pdf off by 15 %, MIS weights that double count.
@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("strategy, bias, shape", [("ems", 0.1, AREA_MEASURE), ("mats", 0.15, UNIFORM),
                                                   ("mis", 0.1, DOUBLE_COUNT)])
def test_a_biased_strategy_is_named(seed, strategy, bias, shape):
    check = compare_strategies(planted(_triple(100 + seed), strategy, bias, shape), spp=SPP)
    assert check.verdict == "DIFFERS" and check.odd == strategy and check.disagree
    others = [s for s in STRATEGIES if s != strategy]
    assert check.reason.startswith(f"{strategy} differs from {others[0]} and {others[1]}, which agree: ")
    assert not check.pair(*others).rejects


def test_a_wrong_light_pdf_is_suspected_in_the_reason():
    check = compare_strategies(planted(_triple(7), "ems", 0.2, AREA_MEASURE), spp=SPP)
    assert check.reason.endswith("suspect the light's sampling or its pdf (a pdf left in area measure?)")
    assert "ems vs mats: FAIL (" in check.reason and "ems vs mis: FAIL (" in check.reason


def test_non_finite_pixels_name_their_strategy():
    triple = _triple(3)
    triple["mats"][2, 5, 7, 1] = np.nan
    check = compare_strategies(triple, spp=SPP)
    assert check.odd == "mats" and "non-finite pixels" in check.reason


def test_two_biased_strategies_name_none():
    triple = planted(planted(_triple(4), "ems", 0.3), "mats", -0.3)
    check = compare_strategies(triple, spp=SPP)
    assert check.verdict == "INCONCLUSIVE" and check.odd is None and check.disagree
    assert check.reason.startswith("every pair disagrees: more than one strategy differs")


def test_two_strategies_wrong_alike_are_suspected_by_the_part_they_share():
    """A light pdf left in area measure biases MIS too where it weighs the light's samples by nearly 1: ems and
    mis are then both wrong, alike, and the check points at the light's sampling; mats and mis alike, at the
    BSDF's. Two strategies wrong in opposite directions leave no pair nearest: no suspects."""
    light = compare_strategies(planted(planted(_triple(11), "ems", 3.0, AREA_MEASURE), "mis", 2.9, AREA_MEASURE),
                               spp=SPP)
    assert light.verdict == "INCONCLUSIVE" and light.odd is None and light.suspects == ("ems", "mis")
    assert "suspect the light's sampling or its pdf, which ems and mis share" in light.reason
    bsdf = compare_strategies(planted(planted(_triple(12), "mats", 0.5), "mis", 0.45), spp=SPP)
    assert bsdf.suspects == ("mats", "mis") and "the BSDF's sampling" in bsdf.reason
    apart = compare_strategies(planted(planted(_triple(4), "ems", 0.3), "mats", -0.3), spp=SPP)
    assert apart.disagree and apart.suspects == () and "nearest" not in apart.reason


def test_a_named_strategy_is_the_only_suspect():
    check = compare_strategies(planted(_triple(13), "mats", 0.3), spp=SPP)
    assert check.odd == "mats" and check.suspects == ("mats",) and check.to_json()["suspects"] == ["mats"]


def _pairs(rejecting: set[tuple[str, str]], inconclusive: str = "") -> tuple[StrategyPair, ...]:
    def outcome(names):
        rejects = names in rejecting
        return SimpleNamespace(passed=not rejects, reason="image scale(s) reject" if rejects else "",
                               inconclusive=inconclusive, verdict="FAIL" if rejects else
                               "INCONCLUSIVE" if inconclusive else "PASS")
    return tuple(StrategyPair(first=a, second=b, comparison=outcome((a, b)))
                 for a, b in (("ems", "mats"), ("ems", "mis"), ("mats", "mis")))


def test_one_disagreeing_pair_names_no_strategy():
    verdict, odd, reason = read_pattern(_pairs({("ems", "mis")}), 0.01, 0.00334)
    assert (verdict, odd) == ("INCONCLUSIVE", None)
    assert reason.startswith("ems and mis disagree while mats agrees with both: no single strategy is named")


def test_each_pair_of_failures_names_the_strategy_they_share():
    for odd, rejecting in (("ems", {("ems", "mats"), ("ems", "mis")}), ("mats", {("ems", "mats"), ("mats", "mis")}),
                           ("mis", {("ems", "mis"), ("mats", "mis")})):
        assert read_pattern(_pairs(rejecting), 0.01, 0.00334)[:2] == ("DIFFERS", odd)


def test_no_rejection_without_power_is_no_agreement():
    verdict, odd, reason = read_pattern(_pairs(set(), "the comparison finds a bias ... only from 0.2 on"), 0.01, 0.003)
    assert (verdict, odd) == ("INCONCLUSIVE", None) and reason.startswith("no comparison rejects, but ems vs mats: ")


def test_too_few_samples_to_resolve_a_bias_is_inconclusive():
    check = compare_strategies(null_triple(np.random.default_rng(5), 16, k=4, spp=1), spp=1)
    assert check.verdict == "INCONCLUSIVE" and not check.disagree and "above the 5% it must resolve" in check.reason


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_blocks_keep_a_heavy_tailed_strategy_from_false_alarms(seed):
    """BSDF sampling that hits the light in 1 % of its samples or fewer: per pixel, most batches miss it and
    Welch's t calls the correct "mats" different (the check's wrong twin: blocks of one pixel); blocks of 8x8
    pixels do not."""
    triple = null_triple(np.random.default_rng(40 + seed), 32, spp=SPP, hits=(0.002, 0.01))
    assert compare_strategies(triple, spp=SPP, block=1).odd == "mats"
    assert not compare_strategies(triple, spp=SPP).disagree  # too few hits to resolve 5 %: INCONCLUSIVE


def test_blocks_are_eight_pixels_or_an_eighth_of_the_image():
    assert [block_side(n, n) for n in (16, 32, 64, 128, 256)] == [8, 8, 8, 16, 32]
    assert block_side(128, 96) == block_side(96, 128) == 16


def test_a_negative_pixel_is_not_averaged_away_in_its_block():
    triple = _triple(9)
    triple["mis"][3, 17, 4, 2] = -0.5
    check = compare_strategies(triple, spp=SPP)
    assert check.odd == "mis" and "negative" in check.reason


def test_renders_and_arrays_are_taken_alike():
    triple = _triple(6)
    results = {name: RenderResult(engine="mcval", scene="s", integrator="direct", spp=SPP, seed=0,
                                  batches=b.astype(np.float32), seconds={}) for name, b in triple.items()}
    from_results = compare_strategies(results)
    from_arrays = compare_strategies({n: b.astype(np.float32) for n, b in triple.items()}, spp=SPP)
    assert from_results.verdict == from_arrays.verdict == "AGREE"
    assert [p.comparison.scales[2].min_p for p in from_results.pairs] == \
        [p.comparison.scales[2].min_p for p in from_arrays.pairs]


def test_bad_inputs_are_refused_in_words():
    triple = _triple(8)
    with pytest.raises(ValueError, match="missing mis; unknown path"):
        compare_strategies({"ems": triple["ems"], "mats": triple["mats"], "path": triple["mis"]})
    results = {n: SimpleNamespace(batches=b, spp=SPP * (2 if n == "mats" else 1)) for n, b in triple.items()}
    with pytest.raises(ValueError, match=r"different samples per pixel \(\[32, 64\]\)"):
        compare_strategies(results)
    with pytest.raises(ValueError, match="strategy 'ems': its batches are not at hand"):
        compare_strategies({**triple, "ems": SimpleNamespace(batches=None)})
    with pytest.raises(ValueError, match="images differ in size: ems 32x32, mats 32x32, mis 32x16"):
        compare_strategies({**triple, "mis": triple["mis"][:, :16]})


def _null_alarms(count: int, level: float, **options) -> np.ndarray:
    """1 where a null triple's check agrees, 0 where any comparison rejects (as p-values for `rates`)."""
    hits = options.pop("hits", HITS)
    checks = [compare_strategies(null_triple(np.random.default_rng(20_000 + i), 32, spp=SPP, hits=hits),
                                 alpha=level, spp=SPP, power=False, **options) for i in range(count)]
    return np.array([0.0 if c.disagree else 1.0 for c in checks])


def test_a_correct_renderer_disagrees_at_most_at_the_level():
    """60 null triples at a level of 0.3 (so that a liberal rate shows in few triples): the rate of triples
    with any rejection is not above its Clopper-Pearson interval."""
    (rate,) = rates(_null_alarms(60, 0.3), 1, (0.3,))
    assert not rate.liberal, rate


def test_the_calibration_catches_a_liberal_check():
    """The check's wrong twin, pixels judged one by one (blocks of 1) on a BSDF sampling that rarely hits the
    light, falls above the same interval."""
    (rate,) = rates(_null_alarms(20, 0.3, block=1, hits=(0.002, 0.01)), 1, (0.3,))
    assert rate.liberal, rate


@pytest.mark.slow
@pytest.mark.parametrize("level", [0.3, 0.05, 0.01])
def test_two_hundred_null_triples_at_each_level(level):
    (rate,) = rates(_null_alarms(200, level), 3, (level,))
    assert not rate.liberal, rate
