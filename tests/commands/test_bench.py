"""`bench` with no case to measure exits 3 and says why, instead of writing an empty page and exiting 0."""
import json

from harness.cli import main
from harness.integrators import entries
from tests.helpers.foreign_renderers import write_engine
from tests.helpers.registered_integrators import PRODUCT


def test_an_engine_with_no_benchmarked_integrator_measures_nothing(tmp_path, capsys):
    engine = write_engine(tmp_path, "faithful", integrators=("normals",))
    out = tmp_path / "results"
    assert main(["bench", "--engines", str(engine), "--out", str(out)]) == 3
    (run,) = [p for p in out.iterdir() if p.is_dir()]
    payload = json.loads((run / "results.json").read_text())
    assert payload["verdict"] == "NOTHING JUDGED" and not payload["pass"]
    assert payload["verdict_reason"].startswith("nothing was measured: none of the ")
    measured = ", ".join(sorted(name for name in PRODUCT if entries()[name].benchmarked))
    assert f"cases is benchmarked: bench measures {measured} " in payload["verdict_reason"]
    assert capsys.readouterr().out.rstrip().endswith("FAIL (nothing was judged)")
    assert not (out / "latest").exists()
