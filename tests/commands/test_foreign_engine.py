"""A run with an engine file and a scene of one's own, end to end: the reports name the engine (its file,
command and version), a failed call's output is kept, every reproduce line repeats the engine, the scene
file and --out, progress reaches a log, and the scene's folder is left as it was."""
import json
import os
import sys
import shutil
import stat
import xml.etree.ElementTree as ET

from harness.cli import main
from harness.commands import output
from harness.images.suite import SCENES_DIR
from tests.helpers.foreign_renderers import write_engine


def _results(out):
    return json.loads((out / "latest" / "results.json").read_text())


def test_an_engine_file_is_named_in_every_output(tmp_path, capsys):
    engine = write_engine(tmp_path, "faithful", name="wrapped")
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:simple", "--out", str(out)]) == 0
    results = _results(out)
    meta = results["image_meta"]
    assert meta["engine file"] == str(engine) and "{scene}" in meta["engine command"]
    assert meta["engine"].startswith("wrapped: ") and results["images"][0]["engine"] == "wrapped"
    assert results["invocation"]["options"] == ["--engine", str(engine), "--out", str(out)]
    page = (out / "latest" / "report.html").read_text()
    assert str(engine) in page and "wrapped against mitsuba" not in page  # the table is the terminal's
    properties = {p.get("name"): p.get("value") for p in ET.parse(out / "latest" / "junit.xml").iter("property")}
    assert properties["engine file"] == str(engine)
    printed = capsys.readouterr()
    assert "wrapped against mitsuba" in printed.out
    assert "images (serial): 1/1 done" in printed.err  # plain progress lines in a log


def test_a_failed_call_keeps_its_output_and_the_reproduce_line_repeats_the_run(tmp_path, capsys):
    engine = write_engine(tmp_path, "exit")
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:normals", "--out", str(out)]) == 1
    (case,) = _results(out)["images"]
    assert case["error"] == "exit render: exited with status 3: error: cannot parse"
    assert case["error_output"].splitlines()[-1] == "error: cannot parse"
    assert len(case["error_output"].splitlines()) == 50
    page = (out / "latest" / "report.html").read_text()
    assert "<pre>" in page and "progress 79" in page
    failure = next(ET.parse(out / "latest" / "junit.xml").iter("failure"))
    assert failure.get("message") == case["error"] and "progress 79" in failure.text
    printed = " ".join(capsys.readouterr().out.split())
    assert (f"mcval images --only plane_point:normals --seed 0 --engine {engine} --out {out}"
            in printed)


def test_a_scene_of_ones_own_is_validated_and_its_folder_left_alone(tmp_path, capsys):
    folder = tmp_path / "their scenes"
    (folder / "meshes").mkdir(parents=True)
    shutil.copy(SCENES_DIR / "sphere_plane.xml", folder / "sphere_plane.xml")
    shutil.copy(SCENES_DIR / "meshes" / "sphere.ply", folder / "meshes" / "sphere.ply")
    for path in (folder / "meshes", folder):
        for p in path.iterdir():
            p.chmod(stat.S_IRUSR | stat.S_IRGRP)
        path.chmod(stat.S_IRUSR | stat.S_IXUSR)
    before = sorted((str(p), p.stat().st_mtime_ns) for p in folder.rglob("*"))
    out = tmp_path / "results"
    try:
        code = main(["images", "--scene", str(folder), "--only", "normals", "--out", str(out)])
    finally:
        folder.chmod(stat.S_IRWXU)
    assert sorted((str(p), p.stat().st_mtime_ns) for p in folder.rglob("*")) == before
    assert code == 0
    (case,) = _results(out)["images"]
    assert case["scene"] == "sphere_plane" and case["scene_file"] == str(folder / "sphere_plane.xml")
    assert case["pass"] and case["reference"].startswith("rendered now")  # never a stored reference of mcval's
    assert (out / ".scenes").is_dir()


def test_tables_take_their_width_from_columns(monkeypatch):
    monkeypatch.setenv("COLUMNS", "97")
    assert output._width() == 97
    monkeypatch.delenv("COLUMNS")
    assert output._width() == (None if os.isatty(1) else output.LOG_WIDTH)


def test_an_engine_file_is_benchmarked_against_the_reference(tmp_path):
    engine = write_engine(tmp_path, "faithful", name="wrapped")
    out = tmp_path / "results"
    assert main(["bench", "--engines", str(engine), "mitsuba", "--only", "plane_point:simple", "--same-sampler",
                 "--max-spp", "2", "--runs", "1", "--throughput-runs", "0", "--seed-runs", "0",
                 "--out", str(out)]) == 0
    (case,) = _results(out)["speed"]
    assert case["efficiency_ratio_same_sampler"]["tested"] == "wrapped/independent"
    assert case["efficiency_ratio_same_sampler"]["reference"] == "mitsuba/independent"


def test_a_renderer_that_ignores_its_seed_fails_as_batches_not_independent(tmp_path, capsys):
    engine = write_engine(tmp_path, "fixed_seed")
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:simple", "--out", str(out)]) == 1
    (case,) = _results(out)["images"]
    independence = case["tests"]["mitsuba"]["independence"]
    assert not case["pass"] and independence["test"]["alike"]
    assert "all 8 test batches are the same image" in independence["summary"]
    assert "batches not independent" in " ".join(capsys.readouterr().out.split())
    failure = next(ET.parse(out / "latest" / "junit.xml").iter("failure"))
    assert "batches not independent" in failure.get("message")


def test_a_renderer_whose_seeds_repeat_fails_as_batches_not_independent(tmp_path):
    engine = write_engine(tmp_path, "seed_mod_4")
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:simple", "--out", str(out)]) == 1
    (case,) = _results(out)["images"]
    test = case["tests"]["mitsuba"]["independence"]["test"]
    assert test["dependent"] and test["correlation"] > 0.99 and not test["alike"]


def test_a_renderer_repeating_the_batches_of_one_call_fails_as_batches_not_independent(tmp_path):
    engine = write_engine(tmp_path, "batched_repeats")  # one call renders all 8: one image, 8 times
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:simple", "--out", str(out)]) == 1
    (case,) = _results(out)["images"]
    independence = case["tests"]["mitsuba"]["independence"]
    assert not case["pass"] and "all 8 test batches are the same image" in independence["summary"]


def test_control_characters_from_an_engine_leave_every_output_readable(tmp_path):
    """Its version and its failed call's output hold C0 controls, DEL, malformed UTF-8 and an encoded lone
    surrogate: results.json, report.html and junit.xml are written and parse, with the characters escaped."""
    dirty = b"v\x00\x01\x08\x0b\x1b[31m\x1f\x7f \xff \xed\xa0\x80 end"
    for name, body in (("ver.py", f"sys.stdout.buffer.write({dirty!r})"),
                       ("bad.py", f"sys.stdout.buffer.write({dirty!r} + b'\\n' + {dirty!r}); sys.exit(2)")):
        (tmp_path / name).write_text(f"#!{sys.executable}\nimport sys\n{body}\n")
        (tmp_path / name).chmod(0o755)
    engine = tmp_path / "bad.toml"
    engine.write_text('name = "bad"\ncommand = ["{here}/bad.py", "{scene}", "{output}"]\n'
                      'version = ["{here}/ver.py"]\n[integrators]\nsimple = "simple"\n')
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:simple", "--out", str(out)]) == 1
    (case,) = _results(out)["images"]
    assert "\\x1b[31m\\x1f\\x7f \ufffd" in case["error"]  # (its vertical tab ends a line)
    tree = ET.parse(out / "latest" / "junit.xml")
    failure = next(tree.iter("failure"))
    assert failure.get("message") == case["error"] and "\\x00" in failure.text
    properties = {p.get("name"): p.get("value") for p in tree.iter("property")}
    assert "v\\x00\\x01\\x08\\x0b\\x1b[31m" in properties["engine"]
    assert "\\x00\\x01" in (out / "latest" / "report.html").read_text()
