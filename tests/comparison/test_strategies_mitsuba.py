"""The strategy check on real renders: Mitsuba's `direct` on its Cornell box with emitter sampling alone, BSDF
sampling alone (most of a pixel's batches miss the small light) and MIS agree; each planted bias is named."""
import pytest

from harness.comparison.strategies import compare_strategies
from harness.engines.python_child import PythonChild
from tools.strategy_renders import CALL_SECONDS
from tools.strategy_triples import AREA_MEASURE, DOUBLE_COUNT, UNIFORM, planted

pytestmark = pytest.mark.mitsuba
SPP = 32


@pytest.fixture(scope="module")
def triples():
    child = PythonChild()
    try:
        return [child.call("tools.strategy_renders:render_triple", 1000 + t, 64, SPP, 8, timeout=CALL_SECONDS)
                for t in range(2)]
    finally:
        child.close()


def test_mitsubas_three_strategies_agree(triples):
    for triple in triples:
        check = compare_strategies(triple, spp=SPP)
        assert check.verdict == "AGREE", check.reason
        # Judged pixel by pixel, BSDF sampling's missed light reads as a difference (the blocks' reason).
        assert compare_strategies(triple, spp=SPP, block=1).odd == "mats"


@pytest.mark.parametrize("strategy, bias, shape", [("ems", 0.1, AREA_MEASURE), ("mats", 0.15, UNIFORM),
                                                   ("mis", 0.1, DOUBLE_COUNT)])
def test_a_biased_strategy_of_mitsuba_is_named(triples, strategy, bias, shape):
    for triple in triples:
        check = compare_strategies(planted(triple, strategy, bias, shape), spp=SPP)
        assert check.odd == strategy, check.reason
