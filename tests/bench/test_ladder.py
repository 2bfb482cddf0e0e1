"""A ladder none of whose sample counts an engine renders exactly is said as such, not a TypeError."""
import pytest

from harness.bench.ladder import run_ladder
from harness.images.suite import ImageCase


class RoundingEngine:
    """An engine whose sampler rounds every sample count (Mitsuba's ldsampler below its smallest)."""

    name, label = "rounding", ""

    def renders_exactly(self, spp: int) -> bool:
        return False

    def render(self, *args, **kwargs):
        raise AssertionError("nothing may be rendered at a count the engine rounds")


def test_an_engine_that_rounds_every_count_is_refused_in_words():
    case = ImageCase(scene="plane_point", integrator="simple")
    with pytest.raises(ValueError, match=r"rounding renders none of the ladder's sample counts \(1, 2 spp\)"):
        run_ladder(RoundingEngine(), case, reference=None, seed=0, ladder=(1, 2))
