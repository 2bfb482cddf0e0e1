"""The real scenes section of an image run: Mitsuba's Cornell box against Mitsuba with normals and ao from
stored references, simple listed as not applicable (not run, not a failure), its own group in results.json."""
import json
import re
import subprocess
from pathlib import Path

import pytest

from harness.cli import main
from harness.engines.mitsuba_scene import mitsuba_xml
from harness.engines.render_process import render_binary
from harness.images.suite import INTEGRATORS

ROOT = Path(__file__).resolve().parents[2]
CORNELL_BOX = ROOT / "scenes" / "real" / "cornell_box.xml"


@pytest.fixture(scope="module")
def real_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("results")
    code = main(["images", "--only", "cornell_box", "--out", str(out)])
    return code, json.loads(((out / "latest").resolve() / "results.json").read_text())


@pytest.mark.slow
def test_the_cornell_box_passes_against_stored_references(real_run):
    code, data = real_run
    assert code == 0 and data["pass"] is True
    group = data["real_scenes"]
    assert group["pass"] is True and group["scenes"] == ["cornell_box"]
    assert [(c["integrator"], c["pass"], c["reference"]) for c in group["cases"]] == \
        [(name, True, "stored reference") for name in INTEGRATORS if name != "simple"]


def test_simple_is_listed_as_not_applicable(real_run):
    _, data = real_run
    assert data["real_scenes"]["not_applicable"] == [
        {"scene": "cornell_box", "integrator": "simple", "reason": "no point light"}]
    assert "simple" not in {e["integrator"] for e in data["images"]}


@pytest.mark.parametrize("integrator", ["normals", "ao"])
def test_mitsuba_loses_exactly_what_our_loader_skips(integrator, tmp_path):
    """Every element our loader notes as skipped is gone from the Mitsuba scene, and nothing else."""
    res = subprocess.run([str(render_binary()), str(CORNELL_BOX), "--integrator", integrator, "--spp", "1",
                          "-D", "res=8", "-q", "-o", str(tmp_path / "o.exr")], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    skipped = re.findall(r"<(\w+) type=\"(\w+)\">", res.stderr)
    original, mapped = CORNELL_BOX.read_text(), mitsuba_xml(CORNELL_BOX.read_text(), integrator)
    count = lambda text, tag, kind: len(re.findall(rf'<{tag} type="{kind}"', text))  # noqa: E731
    assert skipped == [("emitter", "area")]
    assert count(original, "emitter", "area") == 1 and count(mapped, "emitter", "area") == 0
    assert count(mapped, "shape", "rectangle") == count(original, "shape", "rectangle")
    assert count(mapped, "shape", "cube") == count(original, "shape", "cube")
