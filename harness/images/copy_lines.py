"""An engine's error about a --scene file's prepared copy, said in the terms of the file as given: the line of
the copy it names (Mitsuba's "(line N, col M)" of the text it loaded, ours "COPY:N") becomes the user's
FILE:LINE, through the copy's map of source lines (harness/images/scene_copy.py)."""
from __future__ import annotations

import re

from harness.images.suite import ImageCase

#: Mitsuba 3's parser on a scene loaded from a string (the harness loads every copy so).
_MITSUBA_LINE = re.compile(r"(?:Error while loading string )?\(line (\d+), col \d+\)")


def _source_line(case: ImageCase, line: int) -> int:
    return case.source_lines[line] if 0 < line < len(case.source_lines) else 0


def in_user_terms(reason: str, case: ImageCase) -> str:
    """`reason` with the copy's lines named as lines of `case.source`; a copy still named (a line the map does
    not know) is said to be the copy of the file as given."""
    if not case.source:
        return reason
    copy = str(case.path)
    if case.source_lines:
        def mitsuba(match: re.Match) -> str:
            line = _source_line(case, int(match.group(1)))
            return f"in {case.source}:{line}" if line else match.group(0)

        def ours(match: re.Match) -> str:
            line = _source_line(case, int(match.group(1)))
            return f"{case.source}:{line}" if line else match.group(0)

        reason = _MITSUBA_LINE.sub(mitsuba, reason)
        reason = re.sub(re.escape(copy) + r":(\d+)", ours, reason)
    if copy in reason:
        reason = f"{reason} (the prepared copy of {case.source})"
    return reason
