"""`python -m harness invariance`: exit status, results.json's `invariance` block and the page."""
from __future__ import annotations

import json

from harness.cli import main
from tests.helpers.foreign_renderers import write_engine


def test_invariance_command_writes_its_block(tmp_path):
    out = tmp_path / "results"
    code = main(["invariance", "--only", "plane_point", "simple", "light", "reflectance", "--no-mitsuba",
                 "--out", str(out), "--json", str(tmp_path / "inv.json")])
    assert code == 0
    payload = json.loads((out / "latest" / "results.json").read_text())
    block = payload["invariance"]
    assert payload["pass"] and block["pass"] and block["gating_engine"] == "mcval"
    assert [(c["invariance"], c["scene"], c["integrator"]) for c in block["cells"]] == \
        [("light", "plane_point", "simple"), ("reflectance", "plane_point", "simple")]
    assert block["cells"][0]["variants"][0]["ratio"] == block["cells"][0]["ratio"]
    assert (out / "latest" / "invariance.html").read_text().count("PASS") == 2
    assert json.loads((tmp_path / "inv.json").read_text())["invariance"]["failures"] == []


def test_unknown_name_is_bad_input(tmp_path):
    assert main(["invariance", "--only", "nonsense", "--no-mitsuba", "--out", str(tmp_path)]) == 2
    assert not list(tmp_path.iterdir())  # refused before any run folder


def test_the_image_report_carries_the_invariance_matrix_only_when_there_is_one(tmp_path):
    from harness.report.image_html import report_html

    out = tmp_path / "results"
    assert main(["invariance", "--only", "plane_point", "simple", "light", "--no-mitsuba", "--out", str(out)]) == 0
    block = json.loads((out / "latest" / "results.json").read_text())["invariance"]
    page = report_html([], 0.01, None, {}, None, None, invariance=block)
    assert '<a href="invariance.html">own page</a>' in page and 'id="invariances"' in page
    assert "1 of 1 checks of mcval pass" in page and "<td>plane_point:simple</td>" in page
    failed = dict(block, **{"pass": False})
    assert "mcval validation report: <span class=\"fail\"" in report_html([], 0.01, None, {}, None, None,
                                                                          invariance=failed)
    assert "invariance" not in report_html([], 0.01, None, {}, None, None)


def test_a_narrowed_run_renders_the_reference_and_says_why(tmp_path, mitsuba):
    """Stored cells belong to the whole suite's family level: a narrower run renders Mitsuba's cells at the
    references' seed, and results.json and the page say so."""
    out = tmp_path / "results"
    assert main(["invariance", "--only", "plane_point:normals", "--out", str(out)]) == 0
    block = json.loads((out / "latest" / "results.json").read_text())["invariance"]
    sources = block["meta"]["reference_cells"]
    assert (sources["stored"], sources["rendered"]) == (0, 1)
    assert sources["misses"] == ["references/mitsuba/plane_point/invariance-normals.json: stale (alpha changed)"]
    assert block["meta"]["reference_seed"] == 1000
    assert [c["engine"] for c in block["cells"]] == ["mcval"] * 3 + ["mitsuba"] * 3
    assert "mitsuba: every case rendered now" in (out / "latest" / "invariance.html").read_text()


def test_an_all_black_renderer_is_not_judged_and_the_run_says_why(tmp_path, capsys):
    """Black maps to black under every rewrite: no cell is a PASS, and a run that judged none fails (exit 3)."""
    engine = write_engine(tmp_path, "black")
    out = tmp_path / "results"
    assert main(["invariance", "--engine", str(engine), "--only", "plane_point", "simple", "light", "--no-mitsuba",
                 "--out", str(out)]) == 3
    payload = json.loads((out / "latest" / "results.json").read_text())
    (cell,) = payload["invariance"]["cells"]
    assert cell["status"] == "inconclusive" and not cell["pass"] and not payload["pass"]
    assert payload["verdict"] == "NOTHING JUDGED"
    assert payload["verdict_reason"].startswith("nothing was judged: invariance cells of black: 1 cell "
                                                "(plane_point:simple light): the base render is constant (all 0)")
    printed = capsys.readouterr().out
    assert f"FAIL {payload['verdict_reason']}" in " ".join(printed.split())
    assert printed.rstrip().endswith("FAIL (nothing was judged)")


def test_a_renderer_that_ignores_its_seed_fails_with_the_cause_first(tmp_path, capsys):
    engine = write_engine(tmp_path, "fixed_seed")
    out = tmp_path / "results"
    assert main(["invariance", "--engine", str(engine), "--only", "plane_point", "simple", "light", "--no-mitsuba",
                 "--out", str(out)]) == 1
    block = json.loads((out / "latest" / "results.json").read_text())["invariance"]
    first = block["failures"][0]
    assert first.startswith("plane_point:simple (light): batches not independent: all 8 batches of the base render "
                            "are the same image") and first.endswith("is the seed it is given used?")
    printed = [line for line in capsys.readouterr().out.splitlines() if line.startswith("FAIL")]
    assert printed[0] == f"FAIL invariance {first}"
