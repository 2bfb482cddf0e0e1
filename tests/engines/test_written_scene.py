"""The scene an engine file's renderer is given: a malformed size is refused in one line, not a traceback."""
import pytest

from harness.engines.written_scene import written_scene

SCENE = """<scene version="3.0.0">
  {default}
  <sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
  </sensor>
</scene>"""


@pytest.mark.parametrize("default", ['<default name="res"/>', '<default name="res" value="wide"/>',
                                     '<default name="res" value="-4"/>'])
def test_a_size_that_is_no_number_of_pixels_is_a_value_error(tmp_path, default):
    path = tmp_path / "scene.xml"
    path.write_text(SCENE.format(default=default))
    with pytest.raises(ValueError, match="not a whole number of pixels"):
        written_scene(path, {}, "path", 4)


def test_a_good_size_is_kept(tmp_path):
    path = tmp_path / "scene.xml"
    path.write_text(SCENE.format(default='<default name="res" value="12"/>'))
    _, width, height = written_scene(path, {}, "path", 4)
    assert (width, height) == (12, 12)
