"""The command line: help, the warps matrix with its JSON and HTML, and clear errors."""
import json
import subprocess
import sys

import pytest

from harness.cli import main


def test_help_lists_the_subcommands():
    out = subprocess.run([sys.executable, "-m", "harness", "--help"], capture_output=True, text=True)
    assert out.returncode == 0
    assert "warps" in out.stdout and "validate" in out.stdout
    assert out.stdout.startswith("usage: mcval ")  # the installed command's name, also under python -m harness


def test_warps_writes_json_and_html(tmp_path):
    json_path = tmp_path / "warps.json"
    code = main(["warps", "--only", "tent", "beckmann:0.1", "--samples", "200000", "--out", str(tmp_path),
                 "--json", str(json_path)])
    assert code == 0
    data = json.loads(json_path.read_text())
    assert data["pass"] is True
    entries = {(e["warp"], json.dumps(e["params"])): e for e in data["warps"]}
    beckmann = entries[("square_to_beckmann", json.dumps({"alpha": 0.1}))]
    assert set(beckmann["checks"]) == {"chi2", "normalisation", "domain", "pdf_vs_target", "samples_vs_target",
                                       "pdf_vs_mitsuba", "samples_vs_mitsuba", "hard_inputs", "throughput"}
    assert beckmann["target"] == "square_to_beckmann's D(m) cos(theta_m), Beckmann alpha=0.1"
    for check in beckmann["checks"].values():
        assert check["pass"] is True and "figure" in check
    run = tmp_path / "latest"
    assert json.loads((run / "results.json").read_text())["warps"]
    page = (run / "warps.html").read_text()
    assert page.count("data:image/png;base64,") == 2
    assert "judged against square_to_tent&#x27;s (1-|x|)(1-|y|) on [-1,1]^2 (its name) and its own pdf" in page
    assert "<th>samples_vs_target</th>" in page


@pytest.mark.parametrize("verb, option", [("warps", "--only"), ("validate", "--warps-only")])
def test_unknown_warp_is_a_clear_error(tmp_path, capsys, verb, option):
    assert main([verb, option, "tentacle", "--out", str(tmp_path)]) == 2
    assert "unknown warp tentacle" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())  # refused before a run folder


def test_bad_arguments_exit_with_usage():
    with pytest.raises(SystemExit) as e:
        main(["warps", "--samples", "many"])
    assert e.value.code == 2


@pytest.mark.parametrize("wrapped", [False, True])
def test_an_interrupt_is_130_even_when_a_library_wraps_it(tmp_path, monkeypatch, capsys, wrapped):
    """A Ctrl-C or SIGTERM that lands inside an import (Dr.Jit's raises ImportError from the
    KeyboardInterrupt) is still an interruption: exit 130 and the partial output named, not an error."""
    import harness.commands.warps as warps_command

    def interrupted(args, run):
        run.start()
        try:
            raise KeyboardInterrupt("SIGTERM")
        except KeyboardInterrupt as e:
            if wrapped:
                raise ImportError("Encountered an error while initializing the extension.") from e
            raise

    monkeypatch.setattr(warps_command, "run", interrupted)
    assert main(["warps", "--only", "tent", "--out", str(tmp_path)]) == 130
    assert "interrupted: partial output in" in capsys.readouterr().err


def test_every_verdict_has_its_exit_status():
    from harness.cli import EXIT_STATUS
    from harness.verdict import Verdict

    assert EXIT_STATUS == {Verdict.PASS: 0, Verdict.FAIL: 1, Verdict.NOTHING_JUDGED: 3}
