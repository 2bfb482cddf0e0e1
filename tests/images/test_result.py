"""A case's failure text, whichever engine or stage it came from, is bounded and safe when its verdict is
made (harness/foreign_text.py): a 1 MB message does not become a 1 MB entry of results.json."""
from dataclasses import replace

import pytest

from harness.foreign_text import FOREIGN_LIMIT
from harness.images.case_verdict import CaseVerdict
from harness.images.evaluate import failure
from harness.images.result import ImageResult
from harness.images.suite import ImageCase


def test_an_engines_long_message_is_bounded_once():
    result = ImageResult(case=ImageCase("plane_ao", "ao"),
                         decision=failure("Mitsuba: <" + "t" * 1_000_000 + "\x00>", "line\x1b\n" * 200_000))
    assert len(result.error) <= FOREIGN_LIMIT and result.error.startswith("Mitsuba: <ttt")
    assert len(result.error_output) <= FOREIGN_LIMIT and result.error_output.endswith("line\\x1b\n")
    again = replace(result, seed=1, decision=replace(result.decision))
    assert (again.error, again.error_output) == (result.error, result.error_output)


def test_results_are_keyword_only():
    with pytest.raises(TypeError):
        ImageResult(ImageCase("plane_ao", "ao"), failure("x"))  # type: ignore[misc]
    with pytest.raises(TypeError):
        CaseVerdict("FAIL")  # type: ignore[misc]


def test_a_verdict_is_one_of_three():
    with pytest.raises(ValueError, match="PASS, FAIL, INCONCLUSIVE"):
        CaseVerdict(verdict="passed")
