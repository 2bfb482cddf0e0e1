"""An engine's error about a --scene file's prepared copy, said in the terms of the file as given: the line of
the copy it names (Mitsuba's "(line N, col M)" of the text it loaded, mcval's "COPY:N" and the "at line N" of
a second element it names after it) becomes the user's FILE:LINE, through the copy's map of source lines
(harness/images/scene_copy.py)."""
from __future__ import annotations

import re
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from harness.images.suite import ImageCase

#: Mitsuba 3's parser on a scene loaded from a string (the harness loads every copy so): "Error while loading
#: string (line N, col M)" for what it cannot parse, "At string (line N, col M)" for what it cannot instantiate.
_MITSUBA_LINE = re.compile(r"(?:(?:Error while loading|At) string )?\(line (\d+), col \d+\)")
#: mcval's loader naming another element of the file its message is about: "given here as a <ref> at line N".
_AT_LINE = re.compile(r"\bat line (\d+)\b")


def name_lines(reason: str, copy: str, source: str, source_lines: Sequence[int]) -> str:
    """`reason` with each line of the copy it names (Mitsuba's "(line N, col M)", `copy`:N) as
    `source`:LINE, where `source_lines` (per line of the copy, the source's line, 0: none) knows it."""
    def line(n: str) -> int:
        return source_lines[int(n)] if 0 < int(n) < len(source_lines) else 0

    def mitsuba(match: re.Match) -> str:
        return f"in {source}:{line(match.group(1))}" if line(match.group(1)) else match.group(0)

    def path_line(match: re.Match) -> str:
        return f"{source}:{line(match.group(1))}" if line(match.group(1)) else match.group(0)

    def at_line(match: re.Match) -> str:
        return f"at line {line(match.group(1))}" if line(match.group(1)) else match.group(0)

    reason = _MITSUBA_LINE.sub(mitsuba, reason)
    if not copy:
        return reason
    head, about_copy, tail = reason.partition(f"{copy}:")  # what follows the copy's name speaks of the copy
    reason = head + about_copy + (_AT_LINE.sub(at_line, tail) if about_copy else "")
    return re.sub(re.escape(copy) + r":(\d+)", path_line, reason)


def in_user_terms(reason: str, case: ImageCase) -> str:
    """`reason` with the copy's lines named as lines of `case.source`; a copy still named (a line the map does
    not know) is said to be the copy of the file as given."""
    if not case.source:
        return reason
    copy = str(case.path)
    if case.source_lines:
        reason = name_lines(reason, copy, case.source, case.source_lines)
    if copy in reason:
        reason = f"{reason} (the prepared copy of {case.source})"
    return reason
