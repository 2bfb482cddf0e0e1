"""The example renderer through its engine file and the image suite, against closed forms alone (quick, at 16
pixels): its `path` (examples/renderer/pyrender_path.py) and `direct` in the furnace, and its `ao`, which reads no
material, on the lone plane. Each passes, and each planted mistake fails: Russian roulette that does not divide
its survivors by their probability, an ao that multiplies by the reflectance."""
import json
from pathlib import Path

import pytest

from harness.cli import main
from tests.helpers.pyrender_engine import pyrender_engine

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _small(tmp_path, engine: Path, case: str) -> tuple[int, dict]:
    """images of `case` (scene:integrator), 16 pixels wide, against its closed form alone."""
    scene = case.split(":")[0]
    out = tmp_path / "results"
    code = main(["images", "--engine", str(engine), "--scene", str(SCENES / f"{scene}.xml"), "--resolution", "16",
                 "--reference", "analytic", "--only", case, "--out", str(out)])
    (entry,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    return code, entry


@pytest.mark.parametrize("case", ["furnace:path", "furnace:direct", "plane_ao:ao"])
def test_it_matches_the_closed_forms(tmp_path, case):
    code, entry = _small(tmp_path, pyrender_engine(tmp_path), case)
    assert code == 0 and entry["pass"] and entry["engine"] == "pyrender", entry


@pytest.mark.parametrize("bug, case", [("path-rr", "furnace:path"), ("ao-albedo", "plane_ao:ao")])
def test_each_planted_bug_fails_against_the_closed_form(tmp_path, bug, case):
    code, entry = _small(tmp_path, pyrender_engine(tmp_path, bug), case)
    assert code == 1 and not entry["pass"] and entry["engine"] == f"pyrender-{bug}"
