"""The bench's sampler bookkeeping: which ladder steps a Mitsuba sampler renders exactly."""
import pytest


@pytest.mark.parametrize("sampler, exact, rounded", [
    ("independent", (1, 2, 32, 128), ()),
    ("ldsampler", (4, 16, 64, 256), (1, 2, 8, 32, 128)),  # 1 -> 4
    ("multijitter", (1, 2, 4, 8, 16, 64, 256), (32, 128)),  # 32 -> a 5 x 7 grid of 35
])
def test_mitsuba_renders_exactly_what_its_sampler_keeps(sampler, exact, rounded):
    from harness.engines.mitsuba import MitsubaEngine
    engine = MitsubaEngine(sampler=sampler)
    assert all(engine.renders_exactly(n) for n in exact)
    assert not any(engine.renders_exactly(n) for n in rounded)
    assert MitsubaEngine().renders_exactly(32)  # the scene's own sampler: nothing asked


def test_mitsuba_renders_with_the_sampler_it_is_given(tmp_path):
    import re
    from harness.engines.mitsuba import MitsubaEngine
    from harness.images.suite import SCENES_DIR
    scene = SCENES_DIR / "plane_point.xml"
    result = MitsubaEngine(sampler="multijitter").render(str(scene), "simple", 4, 1, 0, {"res": "8"})
    assert result.sampler == "MultijitterSampler"
    # A scene that declares no sampler would get Mitsuba's default under the wrong name: refused.
    bare = tmp_path / "bare.xml"
    bare.write_text(re.sub(r"<sampler .*?</sampler>", "", scene.read_text(), flags=re.S))
    with pytest.raises(RuntimeError, match="declares no <sampler>"):
        MitsubaEngine(sampler="ldsampler").render(str(bare), "simple", 4, 1, 0, {"res": "8"})
    with pytest.raises(ValueError, match="unknown Mitsuba sampler 'sobol'"):
        MitsubaEngine(sampler="sobol")  # mcval; Mitsuba's closest is ldsampler
