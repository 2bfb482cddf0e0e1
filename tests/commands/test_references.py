"""`references` with no case selected stores nothing and exits 3, saying so."""
import harness.images.suite as suite
from harness.cli import main


def test_nothing_selected_is_nothing_stored(monkeypatch, capsys, tmp_path):
    monkeypatch.setattr(suite, "select_cases", lambda *args, **kwargs: [])
    assert main(["references"]) == 3
    assert "nothing was stored: no case of the suite was selected" in capsys.readouterr().out
