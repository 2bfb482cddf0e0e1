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
