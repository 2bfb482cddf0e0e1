"""`validate` is no PASS when a suite it runs judged nothing: it exits 3 and names each such suite and why; it runs
the BSDF matrix of the engine under test (ours, or --bsdf-library), whose failed row fails the run, and says an
engine without a BSDF library has none checked."""
import json
from pathlib import Path

import pytest

from harness.cli import main
from harness.images.suite import REAL_SCENES_DIR
from tests.helpers.foreign_renderers import write_engine
from tests.helpers.warp_libraries import build_warp_library

TWINS = Path(__file__).resolve().parents[1] / "bsdfs" / "bsdf_twins.c"
#: A small validate: one warp, one image case, no invariance.
NARROW = ["--warps-only", "tent", "--only", "plane_point:simple", "--no-invariance"]


def test_validate_with_nothing_to_judge_exits_3(tmp_path):
    engine = write_engine(tmp_path, "faithful", integrators=("simple",))
    out = tmp_path / "results"
    assert main(["validate", "--engine", str(engine), "--scene", str(REAL_SCENES_DIR / "cornell_box.xml"),
                 "--out", str(out)]) == 3
    payload = json.loads((out / "latest" / "results.json").read_text())
    assert [t["what"] for t in payload["judged"]] == ["invariance cells of faithful", "image cases"]
    assert payload["bsdfs_not_checked"].endswith("has no BSDF library (give --bsdf-library LIB.so)")
    assert payload["verdict_reason"].startswith("nothing was judged: invariance cells of faithful: no case of the engine "
                                                "faithful (it renders simple) applies to the scenes: cornell_box:simple")
    assert "; image cases: no case of the engine faithful" in payload["verdict_reason"]


@pytest.mark.mitsuba
def test_validate_runs_our_bsdfs_and_a_failed_row_fails_the_run(tmp_path):
    out = tmp_path / "ours"
    assert main(["validate", *NARROW, "--bsdfs-only", "diffuse:reflectance=0.5", "--out", str(out)]) == 0
    payload = json.loads((out / "latest" / "results.json").read_text())
    assert len(payload["bsdfs"]) == 5 and all(row["pass"] for row in payload["bsdfs"])
    assert {"what": "BSDF rows", "passed": 5, "failed": 0} in [{k: t[k] for k in ("what", "passed", "failed")}
                                                             for t in payload["judged"]]
    assert (out / "latest" / "bsdfs-junit.xml").is_file()
    twins = build_warp_library(TWINS, tmp_path)
    out = tmp_path / "twin"
    assert main(["validate", *NARROW, "--bsdf-library", str(twins), "--bsdfs-only", "no_inv_pi:albedo=0.5",
                 "--out", str(out)]) == 1
    payload = json.loads((out / "latest" / "results.json").read_text())
    assert not payload["pass"] and all("energy" in row["checks"] and not row["checks"]["energy"]["pass"]
                                       for row in payload["bsdfs"])
