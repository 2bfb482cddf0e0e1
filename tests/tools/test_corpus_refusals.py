"""The corpus refusal counter's pieces that decide its counts: which files are scenes, runs without two scenes
of one name, reasons grouped without their file, exception text told apart. No harness run."""
from __future__ import annotations

from pathlib import Path

from tools.corpus_refusals import Tally, chunks, reason_key, scene_files


def test_scene_files_are_every_scene_rooted_xml_below_the_folder(tmp_path):
    (tmp_path / "a" / "b").mkdir(parents=True)
    (tmp_path / "a" / "b" / "deep.xml").write_text('<scene version="3.0.0"/>')
    (tmp_path / "top.xml").write_text("<scene><shape type='sphere'/></scene>")
    (tmp_path / "broken.xml").write_text("<scene")  # not well-formed: the harness must refuse it well
    (tmp_path / "other.xml").write_text("<project/>")
    assert {p.name for p in scene_files(tmp_path)} == {"deep.xml", "top.xml", "broken.xml"}


def test_no_run_holds_two_scenes_of_one_name():
    files = [Path(f"/c/{d}/scene.xml") for d in "abc"] + [Path("/c/x.xml"), Path("/c/y.xml")]
    groups = chunks(files, 2)
    assert sorted(p for g in groups for p in g) == sorted(files)
    assert all(len(g) <= 2 and len({p.stem for p in g}) == len(g) for g in groups)


def test_reasons_group_without_the_file_and_exception_text_is_counted():
    path = Path("/corpus/x/cbox.xml")
    a = reason_key("mcval render: error: /tmp/run/.scenes/1f/cbox.xml:12: <rfilter>: tent (the prepared copy of "
                   "/corpus/x/cbox.xml): python -m harness images --only cbox:ao", path)
    b = reason_key("mcval render: error: /tmp/run/.scenes/9a/cbox.xml:40: <rfilter>: tent (the prepared copy of "
                   "/corpus/x/cbox.xml)", path)
    assert a == b and "python -m harness" not in a
    tally = Tally()
    tally.add_case({"error": "Mitsuba reference: IndexError: list index out of range"}, path)
    tally.add_case({"error": "Mitsuba reference: SceneFileError: x.xml: <include>: no such file"}, path)
    tally.add_case({"error": "x.xml:3: <rfilter>: unsupported rfilter type"}, path)
    tally.add_case({"verdict": "PASS"}, path)
    tally.add_case({"verdict": "INCONCLUSIVE"}, path)
    assert dict(tally.cases) == {"refused": 3, "refused with exception text": 2, "passed": 1, "failed": 1}
