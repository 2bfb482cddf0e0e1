"""The image section's log of unforeseen errors: each case that failed with one becomes a block of errors.log
(its key, its one line, its traceback), and nothing is written when there is none."""
from types import SimpleNamespace

from harness.commands.image_section import ERRORS_LOG, _log_tracebacks


def _result(key, error=None, traceback="", case_traceback=""):
    return SimpleNamespace(case=SimpleNamespace(key=key, traceback=case_traceback), error=error, traceback=traceback)


def test_unforeseen_errors_go_to_the_runs_log(tmp_path):
    _log_tracebacks([_result("a:ao"), _result("b:ao", "internal error: KeyError: 'x'", "Traceback (most recent)\n"),
                     _result("c:ao", "c.xml: its copy could not be prepared", case_traceback="Traceback (c)\n")],
                    tmp_path)
    log = (tmp_path / ERRORS_LOG).read_text()
    assert "== b:ao: internal error: KeyError: 'x'\nTraceback (most recent)" in log
    assert "== c:ao: c.xml: its copy could not be prepared\nTraceback (c)" in log and "a:ao" not in log


def test_no_log_without_errors(tmp_path):
    _log_tracebacks([_result("a:ao")], tmp_path)
    assert not (tmp_path / ERRORS_LOG).exists()
