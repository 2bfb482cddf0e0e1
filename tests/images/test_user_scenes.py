"""Scenes of one's own (--scene): found in files and folders, prepared into the output folder (absolute mesh
paths, the suite's resolution), and bad paths refused in one line."""
import re
import shutil
import xml.etree.ElementTree as ET

import pytest

from harness.images.suite import SCENES_DIR, USER, select_cases
from harness.images.user_scenes import prepare_scenes, scene_files, scene_names
from harness.invariance.suite import select
from tests.helpers.registered_integrators import PRODUCT


def _scene(folder, name="ball", source="sphere_plane.xml"):
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.xml"
    shutil.copy(SCENES_DIR / source, path)
    for mesh in re.findall(r'name="filename" value="([^"]+)"', path.read_text()):  # a missing mesh is refused
        (folder / mesh).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(SCENES_DIR / mesh, folder / mesh)
    return path


def test_a_prepared_copy_names_its_meshes_absolutely_and_takes_the_suites_size(tmp_path):
    path = _scene(tmp_path / "in")
    text = path.read_text()
    (scene,) = prepare_scenes([tmp_path / "in"], tmp_path / "cache", 96)
    assert path.read_text() == text and scene.source == path and scene.prepared.is_relative_to(tmp_path / "cache")
    root = ET.parse(scene.prepared).getroot()
    (mesh,) = [e.get("value") for e in root.iter("string") if e.get("name") == "filename"]
    assert mesh == str(tmp_path / "in" / "meshes" / "sphere.ply")
    film = next(root.iter("film"))
    assert {e.get("name"): e.get("value") for e in film if e.get("name") in ("width", "height")} == \
        {"width": "$res", "height": "$res"}


def test_a_wide_film_keeps_its_aspect(tmp_path):
    path = _scene(tmp_path / "in")
    path.write_text(path.read_text().replace('name="height" value="$res"', 'name="height" value="64"')
                    .replace('name="width" value="$res"', 'name="width" value="128"'))
    (scene,) = prepare_scenes([path], tmp_path / "cache", 96)
    root = ET.parse(scene.prepared).getroot()
    sizes = {e.get("name"): e.get("value") for e in next(root.iter("film")) if e.get("name") in ("width", "height")}
    assert sizes == {"width": "$res", "height": "48"}


def test_the_copy_declares_the_asked_size_over_the_files_own_default(tmp_path):
    path = _scene(tmp_path / "in")  # sphere_plane declares <default name="res" value="128"/>
    (scene,) = prepare_scenes([path], tmp_path / "cache", 64)
    root = ET.parse(scene.prepared).getroot()
    assert [e.get("value") for e in root if e.tag == "default" and e.get("name") == "res"] == ["64"]


@pytest.mark.mitsuba
def test_a_scene_renders_at_the_resolution_asked_for(tmp_path):
    from harness.images.case_renders import CaseRenders
    from harness.images.case_task import CaseJob, run_case_job
    from harness.engines.mitsuba import MitsubaEngine
    from harness.engines.mcval import McvalEngine

    (scene,) = prepare_scenes([_scene(tmp_path / "in", source="plane_point.xml")], tmp_path / "cache", 40)
    (case,) = select_cases(["ball:normals"], user=[scene])
    result, _ = run_case_job(CaseJob(case=case, seed=1, alpha=0.01, run_seed=0, closed_form=False,
                                          renders=CaseRenders(McvalEngine(), MitsubaEngine())))
    assert result.error is None, result.error
    assert result.tested.mean.shape == (40, 40, 3) and result.passed


def test_bad_paths_are_one_line(tmp_path):
    with pytest.raises(ValueError, match="no such file or folder"):
        scene_files([tmp_path / "nope.xml"])
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="a folder without .xml scene files"):
        scene_files([tmp_path / "empty"])


def test_scenes_of_one_name_are_told_apart_by_their_folders(tmp_path):
    files = [_scene(tmp_path / "x" / "a"), _scene(tmp_path / "y" / "a"), _scene(tmp_path / "b"),
             _scene(tmp_path / "c", "other")]
    assert scene_names(files) == ["x-a-ball", "y-a-ball", "b-ball", "other"]
    scenes = prepare_scenes([tmp_path / "x", tmp_path / "y", tmp_path / "b"], tmp_path / "cache", 16)
    assert sorted(s.name for s in scenes) == ["b-ball", "x-a-ball", "y-a-ball"]
    assert all(s.prepared.name == f"{s.name}.xml" for s in scenes)


def test_user_scenes_replace_the_suite_or_join_it(tmp_path):
    user = prepare_scenes([_scene(tmp_path / "in", "ball")], tmp_path / "cache", 128)
    cases = select_cases(None, user=user)
    assert {c.scene for c in cases} == {"ball"} and all(c.group == USER for c in cases)
    assert {c.integrator for c in cases} == set(PRODUCT)
    both = select_cases(None, user=user, with_suite=True)
    assert {"ball", "cornell"} <= {c.scene for c in both}
    clash = prepare_scenes([_scene(tmp_path / "in2", "cornell")], tmp_path / "cache", 128)
    with pytest.raises(ValueError, match="the suite has a scene called cornell too"):
        select_cases(None, user=clash, with_suite=True)
    invariance_cases, _ = select(["ball:ao", "scale"], user=user)
    assert [c.key for c in invariance_cases] == ["ball:ao"] and invariance_cases[0].scene == user[0].prepared


def test_a_film_size_given_by_parameters_takes_their_defaults(tmp_path):
    path = _scene(tmp_path / "in")
    text = path.read_text().replace('name="width" value="$res"', 'name="width" value="$resx"') \
        .replace('name="height" value="$res"', 'name="height" value="$resy"')
    path.write_text(text.replace("<scene version=\"3.0.0\">", '<scene version="3.0.0"><default name="resx" '
                                 'value="200"/><default name="resy" value="100"/>', 1))
    (scene,) = prepare_scenes([path], tmp_path / "cache", 96)
    root = ET.parse(scene.prepared).getroot()
    sizes = {e.get("name"): e.get("value") for e in next(root.iter("film")) if e.get("name") in ("width", "height")}
    assert sizes == {"width": "$res", "height": "48"}


def test_a_nori_file_is_prepared_as_mitsubas_and_one_without_a_translation_carries_why(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    (folder / "quad.obj").write_text("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n")
    nori = ('<scene>\n<integrator type="{}"/>\n<mesh type="obj"><string name="filename" value="quad.obj"/></mesh>\n'
            '<camera type="perspective"><integer name="width" value="64"/><integer name="height" value="32"/>'
            '</camera>\n</scene>\n')
    (folder / "good.xml").write_text(nori.format("normals"))
    (folder / "bad.xml").write_text(nori.format("normals").replace('camera type="perspective"',
                                                                   'camera type="thinlens"'))
    (folder / "noted.xml").write_text(nori.format("whitted"))
    bad, good, noted = prepare_scenes([folder], tmp_path / "cache", 96)
    root = ET.parse(good.prepared).getroot()
    assert good.problem == "" and root.find("sensor") is not None and root.find("camera") is None
    (mesh,) = [e.get("value") for e in root.iter("string") if e.get("name") == "filename"]
    assert mesh == str(folder / "quad.obj")
    sizes = {e.get("name"): e.get("value") for e in root.find("sensor/film") if e.get("name") in ("width", "height")}
    assert sizes == {"width": "$res", "height": "48"}
    assert bad.problem.startswith(f"{folder / 'bad.xml'}:4: <camera type=\"thinlens\">")
    # An integrator of Nori's that none of mcval's computes is left out with a note; the scene still renders.
    assert noted.problem == "" and len(noted.notes) == 1
    assert noted.notes[0].startswith(f"{folder / 'noted.xml'}:2: <integrator type=\"whitted\">: not compared")
    (noted_case,) = select_cases(["noted:normals"], user=[bad, good, noted])
    assert noted_case.notes == noted.notes  # carried to the results and the report
    from harness.images.evaluate import failure
    from harness.images.result import ImageResult
    assert ImageResult(case=noted_case, decision=failure("x")).to_json()["scene_notes"] == list(noted.notes)
    (case,) = [c for c in select_cases(["bad:normals"], user=[bad, good])]
    assert case.problem == bad.problem


def test_folders_are_searched_recursively_but_not_hidden_ones_nor_the_runs_output(tmp_path):
    _scene(tmp_path / "in", "top")
    _scene(tmp_path / "in" / "a" / "b", "nested")
    _scene(tmp_path / "in" / ".git", "hidden")
    _scene(tmp_path / "in" / "results" / ".scenes" / "x", "copy")
    _scene(tmp_path / "in" / "results" / "run", "output")
    found = scene_files([tmp_path / "in"], skip=(tmp_path / "in" / "results",))
    assert sorted(p.stem for p in found) == ["nested", "top"]


@pytest.mark.parametrize("name", ["DIR", "x" * 5000])
def test_a_file_the_scene_names_that_cannot_be_read_is_its_scenes_problem_in_words(tmp_path, name):
    """An <include> of a folder, or of a name longer than the system allows: one line, no exception class."""
    (tmp_path / "DIR").mkdir()
    path = tmp_path / "s.xml"
    path.write_text(f'<scene version="3.0.0"><include filename="{name}"/></scene>')
    scene, = prepare_scenes([path], tmp_path / "cache", 16)
    why = "not a regular file" if name == "DIR" else "no such file"
    assert why in scene.problem or "cannot read" in scene.problem, scene.problem
    assert "Error" not in scene.problem and "\n" not in scene.problem


#: How a scene names a file, and the line that names it: a mesh's file name, or an <include> (followed before the
#: file names are checked).
NAMED_BY = {"mesh": ('<shape type="ply">\n<string name="filename" value="{}"/>\n</shape>', 3),
            "include": ('<include filename="{}"/>', 2)}


@pytest.mark.parametrize("named_by", NAMED_BY)
@pytest.mark.parametrize("kind", ["fifo", "device", "folder"])
def test_a_file_that_is_no_regular_file_is_refused_with_its_line(tmp_path, kind, named_by):
    """Reading a named pipe blocks for ever and /dev/zero never ends: refused before any engine opens them, or
    the harness reads them."""
    import os
    target = {"fifo": tmp_path / "FIFO", "device": "/dev/zero", "folder": tmp_path / "DIR"}[kind]
    if kind == "fifo":
        os.mkfifo(target)
    elif kind == "folder":
        target.mkdir()
    element, line = NAMED_BY[named_by]
    path = tmp_path / "s.xml"
    path.write_text(f'<scene version="3.0.0">\n{element.format(target)}\n</scene>')
    scene, = prepare_scenes([path], tmp_path / "cache", 16)
    assert scene.problem.startswith(f"{path}:{line}:") and "not a regular file" in scene.problem, scene.problem
