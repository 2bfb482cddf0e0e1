"""Nori's scene tests in `images --nori-test`: each `<scene>` of each file rendered by the engine under test and
judged by Nori's t-test against its stated reference (harness/images/nori_scene_tests.py)."""
from __future__ import annotations

from pathlib import Path

from harness.commands.output import console
from harness.verdict import Tally


def run_nori_scene_tests(paths: list[Path], engine, run_dir: Path, seed: int) -> tuple[Tally, dict]:
    """The tally of Nori's verdicts and the results.json block; the scenes' copies go to run_dir/nori_tests."""
    from rich.markup import escape

    from harness.engines.nori.test_files import read_nori_test
    from harness.images.nori_scene_tests import run_scene_test

    tests = [read_nori_test(p) for p in paths]  # every file read before any renders: a typo fails at once
    of_bsdfs = next((t for t in tests if not t.scenes), None)
    if of_bsdfs is not None:
        raise ValueError(f"{of_bsdfs.path}: a {of_bsdfs.kind} of BSDFs, not of scenes: run it with "
                         f"`bsdfs --nori-test {of_bsdfs.path}`")
    folder = run_dir / "nori_tests"
    folder.mkdir(parents=True, exist_ok=True)
    block, passed, failed, not_run = [], 0, 0, []
    for test in tests:
        console.print(f"Nori's ttest: {test.path} ({len(test.scenes)} scenes, {engine.label or engine.name})")
        verdicts = run_scene_test(test, engine, folder, seed)
        for v in verdicts:
            mark = {True: "[green]PASS[/]", False: "[red]FAIL[/]", None: "[yellow]NOT RUN[/]"}[v.passed]
            console.print(f"  {mark} {escape(v.scene)} ({escape(v.integrator)}): {escape(v.message)}",
                          soft_wrap=True)
        ok, bad = sum(v.passed is True for v in verdicts), sum(v.passed is False for v in verdicts)
        console.print(f"  Passed {ok}/{len(verdicts)} tests.")
        passed, failed = passed + ok, failed + bad
        not_run += [f"{v.scene}: {v.message}" for v in verdicts if v.passed is None]
        block.append({"file": str(test.path), "kind": test.kind, "tests": [v.to_json() for v in verdicts]})
    return Tally("Nori's scene tests", passed, failed, tuple(not_run)), {"nori_tests": block}
