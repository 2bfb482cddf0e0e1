"""`validate` is no PASS when a suite it runs judged nothing: it exits 3 and names each such suite and why."""
import json

from harness.cli import main
from harness.images.suite import REAL_SCENES_DIR
from tests.helpers.foreign_renderers import write_engine


def test_validate_with_nothing_to_judge_exits_3(tmp_path):
    engine = write_engine(tmp_path, "faithful", integrators=("simple",))
    out = tmp_path / "results"
    assert main(["validate", "--engine", str(engine), "--scene", str(REAL_SCENES_DIR / "cornell_box.xml"),
                 "--out", str(out)]) == 3
    payload = json.loads((out / "latest" / "results.json").read_text())
    assert [t["what"] for t in payload["judged"]] == ["invariance cells of faithful", "image cases"]
    assert payload["verdict_reason"].startswith("nothing was judged: invariance cells of faithful: no case of the engine "
                                                "faithful (it renders simple) applies to the scenes: cornell_box:simple")
    assert "; image cases: no case of the engine faithful" in payload["verdict_reason"]
