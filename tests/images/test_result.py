"""A case's failure text, whichever engine or stage it came from, is bounded and safe when its result is
made (harness/foreign_text.py): a 1 MB message does not become a 1 MB entry of results.json."""
from dataclasses import replace

from harness.foreign_text import FOREIGN_LIMIT
from harness.images.result import ImageResult
from harness.images.suite import ImageCase


def test_an_engines_long_message_is_bounded_once():
    result = ImageResult(ImageCase("plane_ao", "ao"), None, {}, {}, "", 0,
                         error="Mitsuba: <" + "t" * 1_000_000 + "\x00>", error_output="line\x1b\n" * 200_000)
    assert len(result.error) <= FOREIGN_LIMIT and result.error.startswith("Mitsuba: <ttt")
    assert len(result.error_output) <= FOREIGN_LIMIT and result.error_output.endswith("line\\x1b\n")
    again = replace(result, seed=1)
    assert (again.error, again.error_output) == (result.error, result.error_output)
