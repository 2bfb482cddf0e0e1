"""The fuzz campaign of `images --scene` and its verdict: deterministic variants, every mutation changes the file,
each kind of broken run recognised, a whole-run break traced to its variant. No harness run: the verdict is
given the outputs and files a run leaves, and the kill path a stand-in command."""
from __future__ import annotations

import argparse
import json
import random
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fuzz_images  # noqa: E402
import images_outcome  # noqa: E402
from images_outcome import Finding, judge_run  # noqa: E402
from mutate_harness import MUTATIONS  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def test_variants_are_the_same_for_the_same_seed(tmp_path):
    seeds = fuzz_images.harness_seeds()
    for index in (0, 5, 77, 301):
        a = fuzz_images.make_harness_variant(index, 9, seeds, tmp_path / "a")
        b = fuzz_images.make_harness_variant(index, 9, seeds, tmp_path / "b")
        assert (a.seed, a.mutation, a.scene.name) == (b.seed, b.mutation, b.scene.name) == (a.seed, a.mutation,
                                                                                             f"v{index}.xml")
        files = sorted(p.relative_to(a.scene.parent) for p in a.scene.parent.rglob("*")
                       if p.is_file() and not p.is_symlink() and p.name != "FIFO")
        for f in files:
            assert (a.scene.parent / f).read_bytes() == (b.scene.parent / f).read_bytes(), f


@pytest.mark.parametrize("name", sorted(MUTATIONS))
def test_each_harness_mutation_changes_the_scene(tmp_path, name):
    xml = (ROOT / "scenes" / "cornell.xml").read_bytes()
    changed = 0
    for i in range(8):
        folder = tmp_path / f"v{i}"
        folder.mkdir()
        changed += MUTATIONS[name][0](random.Random(i), xml, folder) != xml
    assert changed >= 4, f"{name} changed {changed} of 8"


def _run_folder(tmp_path: Path, cases: list[dict], junit: str = "<testsuites/>") -> Path:
    out = tmp_path / "out"
    (out / "run").mkdir(parents=True)
    (out / "run" / "results.json").write_text(json.dumps({"images": cases, "verdict": "FAIL"}))
    (out / "run" / "junit.xml").write_text(junit)
    return out


def test_a_clean_run_with_refused_cases_has_no_findings(tmp_path):
    out = _run_folder(tmp_path, [{"scene": "v1", "error": "v1.xml:3: expected a finite number", "verdict": "FAIL"}])
    assert judge_run(1, "", "FAIL v1:ao — v1.xml:3: expected a finite number\n", out, ["v1", "v2"]) == []


@pytest.mark.parametrize("rc, killed, outcome", [(-11, "", "signal"), (2, "", "exit-status"), (None, "hang: no exit",
                                                  "hang"), (None, "memory: more than 1 MiB", "memory")])
def test_a_broken_run_is_a_finding_of_the_whole_run(tmp_path, rc, killed, outcome):
    (found,) = judge_run(rc, killed, "images: 0/3 done\n", _run_folder(tmp_path, []), ["v1"])
    assert (found.outcome, found.scene) == (outcome, None)


def test_exception_text_is_found_in_cases_and_output_and_given_to_its_scene(tmp_path):
    out = _run_folder(tmp_path, [{"scene": "v1", "error": "Mitsuba reference: IndexError: list index out of range"},
                                 {"scene": "v2", "idiff": {"reason": "Mitsuba reference: RuntimeError: [parser.cpp:451] "
                                                                     "Error while loading"}},
                                 {"scene": "v3", "error": "SceneFileError: v3.xml: <include>: no such file"}])
    found = judge_run(1, "", "Traceback (most recent call last):\n  File x\nRecursionError: maximum recursion depth "
                             "exceeded\n", out, ["v1", "v2", "v3"])
    assert {(f.outcome, f.scene) for f in found} == {("traceback", "v1"), ("exception-text", "v2"),
                                                     ("exception-text", "v3"), ("traceback", None)}


def test_missing_results_and_a_broken_junit_are_findings(tmp_path):
    assert [f.outcome for f in judge_run(1, "", "", tmp_path / "nothing", ["v1"])] == ["no-results"]
    out = _run_folder(tmp_path, [], junit="<testsuite><testcase name='\x01'/></testsuite>")
    assert [f.outcome for f in judge_run(0, "", "", out, ["v1"])] == ["junit"]


@pytest.mark.parametrize("program, outcome", [("while True: pass", "hang"),  # its CPU seconds
                                              ("import time; time.sleep(30)", "hang"),  # no CPU for 10 s
                                              ("b = bytearray(400 << 20); import time; time.sleep(30)", "memory")])
def test_a_hung_or_swelling_run_is_killed(tmp_path, monkeypatch, program, outcome):
    monkeypatch.setattr(images_outcome, "images_command", lambda *a: [sys.executable, "-c", program])
    rc, killed, _, seconds = images_outcome.run_images([], tmp_path / "out", 8, 0, timeout=0.75,
                                                       memory_limit=100 << 20)
    assert rc is None and killed.startswith(outcome) and seconds < 10, killed


def test_a_blocked_run_is_a_hang_before_its_time_limit(tmp_path, monkeypatch):
    monkeypatch.setattr(images_outcome, "images_command", lambda *a: [sys.executable, "-c", "import time; time.sleep(30)"])
    monkeypatch.setattr(images_outcome, "IDLE_SECONDS", 1.0)
    rc, killed, _, seconds = images_outcome.run_images([], tmp_path / "out", 8, 0, timeout=60, memory_limit=1 << 40)
    assert rc is None and "no CPU used" in killed and seconds < 5, killed


def test_a_whole_run_break_is_traced_to_its_variant(tmp_path, monkeypatch):
    """Variant 6 ends any run it is in; variant 2 has a case with exception text: both are found, and no other."""
    def fake_run(scenes, out, resolution, seed, timeout, memory_limit):
        names = [p.stem for p in scenes]
        findings = [Finding("exception-text", "ValueError: x", "v2")] if "v2" in names else []
        findings += [Finding("signal", "SIGSEGV")] if "v6" in names else []
        return images_outcome.BatchRun(1, 0.1, "", findings)

    monkeypatch.setattr(fuzz_images, "run_batch", fake_run)
    args = argparse.Namespace(work=tmp_path, timeout=1, per_variant_timeout=1, memory_limit=1, seed=0)
    campaign = fuzz_images.Campaign(args)
    variants = [fuzz_images.Variant(i, "s", "m", tmp_path / f"v{i}" / f"v{i}.xml") for i in range(10)]
    found = campaign.batch(variants, 8, "b0")
    assert sorted({(v.index, f.outcome) for v, f in found}) == [(2, "exception-text"), (6, "signal")]
    assert campaign.runs <= 9
