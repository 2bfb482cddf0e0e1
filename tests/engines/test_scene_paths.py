"""<path> and <include> followed as Mitsuba follows them: includes inlined in place, file names found in the
<path> folders first, then the scene's own; one line for what leads nowhere."""
import shutil
import xml.etree.ElementTree as ET

import pytest

from harness.engines.scene_paths import SceneFileError, absolute_paths
from harness.images.suite import SCENES_DIR


def _tree(tmp_path):
    """scenes/main.xml: <path value="../common"/>, an include of fragments/camera.xml (itself including
    fragments/film.xml), a PLY from common/meshes and a rectangle."""
    (tmp_path / "common" / "meshes").mkdir(parents=True)
    (tmp_path / "scenes" / "fragments").mkdir(parents=True)
    shutil.copy(SCENES_DIR / "meshes" / "highpoly.ply", tmp_path / "common" / "meshes" / "ball.ply")
    (tmp_path / "scenes" / "fragments" / "film.xml").write_text(
        '<scene version="3.0.0"><default name="res" value="32"/></scene>')
    (tmp_path / "scenes" / "fragments" / "camera.xml").write_text(
        '<scene version="3.0.0"><include filename="fragments/film.xml"/>'
        '<sensor type="perspective"><float name="fov" value="40"/>'
        '<transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>'
        '<film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>'
        '</sensor></scene>')
    main = tmp_path / "scenes" / "main.xml"
    main.write_text('<scene version="3.0.0"><path value="../common"/><include filename="fragments/camera.xml"/>'
                    '<shape type="ply"><string name="filename" value="meshes/ball.ply"/></shape>'
                    '<shape type="rectangle"/></scene>')
    return main


def test_includes_are_inlined_in_place_and_files_found_in_the_path_folders(tmp_path):
    main = _tree(tmp_path)
    root = ET.parse(main).getroot()
    absolute_paths(root, main)
    assert [e.tag for e in root] == ["default", "sensor", "shape", "shape"]
    (mesh,) = [e.get("value") for e in root.iter("string") if e.get("name") == "filename"]
    assert mesh == str((tmp_path / "common" / "meshes" / "ball.ply").resolve())


@pytest.mark.parametrize("body, message", [
    ('<path value="../nowhere"/>', "no such folder"),
    ('<include filename="fragments/none.xml"/>', "not found in"),
    ('<include filename="main.xml"/>', "includes itself"),
])
def test_what_leads_nowhere_is_one_line_naming_the_file(tmp_path, body, message):
    main = tmp_path / "main.xml"
    main.write_text(f'<scene version="3.0.0">{body}<shape type="rectangle"/></scene>')
    with pytest.raises(SceneFileError, match=message) as raised:
        absolute_paths(ET.parse(main).getroot(), main)
    assert str(main) in str(raised.value) and "\n" not in str(raised.value)


def test_both_engines_render_a_scene_that_includes_its_camera(tmp_path, mcval, mitsuba):
    from harness.images.user_scenes import prepare_scenes
    (scene,) = prepare_scenes([_tree(tmp_path)], tmp_path / "cache", 16)
    mine = mcval.render(str(scene.prepared), "normals", 1, 1, 0, {"res": "16"})
    theirs = mitsuba.render(str(scene.prepared), "normals", 1, 1, 0, {"res": "16"})
    assert mine.batches.shape == theirs.batches.shape == (1, 16, 16, 3)
    assert (abs(mine.batches).sum(axis=-1) > 0).mean() > 0.2  # the ball and the rectangle are in view


def test_a_path_in_an_included_file_is_found_as_mitsuba_finds_it(tmp_path):
    """Mitsuba resolves <path> against the saying file's folder, else against its resolver's folders (the
    main file's, and those named before): Mitsuba's documentation scenes include files that say the main
    file's <path value="../../common"/> again from one folder deeper."""
    (tmp_path / "common" / "meshes").mkdir(parents=True)
    (tmp_path / "docs" / "scenes" / "include").mkdir(parents=True)
    shutil.copy(SCENES_DIR / "meshes" / "sphere.ply", tmp_path / "common" / "meshes" / "ball.ply")
    (tmp_path / "docs" / "scenes" / "include" / "shapes.xml").write_text(
        '<scene version="3.0.0"><path value="../../common"/>'
        '<shape type="ply"><string name="filename" value="meshes/ball.ply"/></shape></scene>')
    main = tmp_path / "docs" / "scenes" / "main.xml"
    main.write_text('<scene version="3.0.0"><include filename="include/shapes.xml"/></scene>')
    root = ET.parse(main).getroot()
    absolute_paths(root, main)
    (mesh,) = [e.get("value") for e in root.iter("string") if e.get("name") == "filename"]
    assert mesh == str((tmp_path / "common" / "meshes" / "ball.ply").resolve())


def test_what_leads_nowhere_names_its_line_when_the_lines_are_known(tmp_path):
    from harness.engines.nori.lined_xml import parse_lined

    main = tmp_path / "main.xml"
    text = '<scene version="3.0.0">\n<shape type="rectangle"/>\n\n<include filename="none.xml"/></scene>'
    main.write_text(text)
    doc = parse_lined(text, main)
    with pytest.raises(SceneFileError, match=rf"^{main}:4: <include filename=\"none.xml\">: not found in"):
        absolute_paths(doc.root, main, doc.lines)
