"""The examples of examples/ run as a user would run them: the small renderer of another design through its
engine file (correct at three seeds; each planted bug fails the suite that names it), and the C++ warp
library (tests/warps/test_warp_library.py)."""
import json
from pathlib import Path

import pytest

from harness.cli import main
from tests.helpers.pyrender_engine import pyrender_engine


def _run(tmp_path, command: str, engine: Path, only: list[str], seed: int = 0) -> tuple[int, dict]:
    out = tmp_path / f"results-{engine.stem}-{seed}"
    extra = ["--no-mitsuba"] if command == "invariance" else []
    code = main([command, "--engine", str(engine), "--only", *only, "--seed", str(seed), "--out", str(out), *extra])
    return code, json.loads((out / "latest" / "results.json").read_text())


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_example_renderer_passes(tmp_path, seed):
    code, results = _run(tmp_path, "images", pyrender_engine(tmp_path), ["cornell:ao"], seed)
    assert code == 0 and [e["pass"] for e in results["images"]] == [True]


@pytest.mark.slow
@pytest.mark.parametrize("bug, case", [("bright", "plane_point:simple"), ("simple-no-cosine", "plane_point:simple"),
                                       ("ao-uniform", "cornell:ao")])
def test_each_planted_bug_fails_the_image_suite(tmp_path, bug, case):
    code, results = _run(tmp_path, "images", pyrender_engine(tmp_path, bug), [case])
    (entry,) = results["images"]
    assert code == 1 and not entry["pass"] and entry["engine"] == f"pyrender-{bug}"
    assert not entry["tests"]["mitsuba"]["pass"]


@pytest.mark.slow
def test_an_absolute_ray_offset_fails_the_scale_invariance(tmp_path, capsys):
    engine = pyrender_engine(tmp_path, "offset")
    code, results = _run(tmp_path, "invariance", engine, ["sphere_plane:ao", "scale"])
    cells = results["invariance"]["cells"]
    assert code == 1 and any(c["invariance"] == "scale" and not c["pass"] for c in cells)
    printed = " ".join(capsys.readouterr().out.split())
    assert f"reproduce: mcval invariance --only sphere_plane:ao scale --seed 0 --engine {engine}" in printed
