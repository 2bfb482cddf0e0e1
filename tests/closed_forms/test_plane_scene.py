"""load_plane_scene reads the closed forms' scenes and refuses, as NotAnalytic, the ones they do not model."""
from pathlib import Path

import pytest

from harness.closed_forms.plane_scene import NotAnalytic, load_plane_scene

PLANE = Path(__file__).resolve().parents[2] / "scenes" / "plane_point.xml"


def test_an_orthographic_sensor_is_not_a_closed_form_case(tmp_path):
    assert load_plane_scene(PLANE).kind == "plane"
    text = PLANE.read_text()
    assert text.count('<sensor type="perspective">') == 1
    orthographic = tmp_path / "orthographic.xml"
    orthographic.write_text(text.replace('<sensor type="perspective">', '<sensor type="orthographic">'))
    with pytest.raises(NotAnalytic, match="perspective sensor"):
        load_plane_scene(orthographic)


@pytest.mark.parametrize("framing", ['<integer name="crop_width" value="4"/>',
                                     '<integer name="crop_offset_y" value="7"/>',
                                     '<boolean name="sample_border" value="true"/>'])
def test_a_film_framed_otherwise_is_not_a_closed_form_case(tmp_path, framing):
    """The closed form renders the whole film: a crop would be compared with an image of another size."""
    text = PLANE.read_text()
    framed = tmp_path / "framed.xml"
    framed.write_text(text.replace('<film type="hdrfilm">', '<film type="hdrfilm">' + framing, 1))
    with pytest.raises(NotAnalytic, match="whole film"):
        load_plane_scene(framed)


def test_a_principal_point_offset_is_not_a_closed_form_case(tmp_path):
    text = PLANE.read_text()
    shifted = tmp_path / "shifted.xml"
    shifted.write_text(text.replace('<sensor type="perspective">',
                                    '<sensor type="perspective"><float name="principal_point_offset_x" value="0.1"/>', 1))
    with pytest.raises(NotAnalytic, match="principal_point_offset_x"):
        load_plane_scene(shifted)
