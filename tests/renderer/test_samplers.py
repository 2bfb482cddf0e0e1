"""The sampler is what the scene says: mcval reads independent and sobol, renders Mitsuba's stratified kinds
as sobol, refuses others with the line, and Mitsuba is handed its closest sampler for mcval."""
from pathlib import Path

import pytest

from harness.engines.base import RenderFailed
from harness.engines.mitsuba_scene import mitsuba_xml

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _with_sampler(tmp_path: Path, kind: str) -> Path:
    text = (SCENES / "plane_point.xml").read_text().replace('<sampler type="independent">',
                                                            f'<sampler type="{kind}">')
    path = tmp_path / f"plane_{kind}.xml"
    path.write_text(text)
    return path


def test_our_renderer_renders_with_the_declared_sampler(mcval, tmp_path):
    params = {"res": "16"}
    assert mcval.render(str(SCENES / "plane_point.xml"), "simple", 4, 2, 0, params).sampler == "independent"
    assert mcval.render(str(_with_sampler(tmp_path, "sobol")), "simple", 4, 2, 0, params).sampler == "sobol"


@pytest.mark.parametrize("kind", ["stratified", "multijitter", "orthogonal", "ldsampler"])
def test_mitsubas_stratified_samplers_render_as_sobol(mcval, tmp_path, kind):
    assert mcval.render(str(_with_sampler(tmp_path, kind)), "simple", 4, 1, 0, {"res": "16"}).sampler == "sobol"


def test_an_unknown_sampler_is_an_error_with_its_line(mcval, tmp_path):
    with pytest.raises(RenderFailed, match=r"plane_halton\.xml:\d+: .*expected independent, stratified, multijitter"):
        mcval.render(str(_with_sampler(tmp_path, "halton")), "simple", 4, 1, 0, {"res": "16"})


def test_mitsuba_gets_ldsampler_for_sobol(tmp_path):
    text = mitsuba_xml(_with_sampler(tmp_path, "sobol").read_text(), "simple")
    assert '<sampler type="ldsampler">' in text and "sobol" not in text
    assert '<sampler type="independent">' in mitsuba_xml((SCENES / "plane_point.xml").read_text(), "simple")
