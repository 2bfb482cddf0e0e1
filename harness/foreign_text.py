"""Text from outside the harness (an engine's version line, what a failed call printed, a renderer's or a
library's error message), made safe before it is stored: bounded in length, and holding only characters that
results.json, an HTML page and junit.xml can carry (XML 1.0 forbids most control characters, and a lone
surrogate cannot be written as UTF-8). What a child process printed (child_process.output_tail, and so every
render failure's reason and output), an engine file's version line and an image case's failure
(ImageResult.error and error_output, whichever engine or stage it came from) pass through `foreign`; every
text file the harness writes (results.write_atomic: results.json, the pages, junit.xml) through `xml_safe`.

Public API::

    foreign(text, limit=FOREIGN_LIMIT, keep="head")  # bounded and safe
    xml_safe(text)                                    # safe, not bounded
    one_line(text, limit=LINE_LIMIT)                  # on one line, printable, bounded
"""
from __future__ import annotations

import re

#: Characters kept of one foreign text: a version line printing 100 MB must not make a 600 MB results.json.
FOREIGN_LIMIT = 4000

# What XML 1.0 does not allow (its Char production), plus DEL and the C1 controls, which no report should
# show raw: each is written as a visible escape instead, so a message keeps its length and says what was there.
_UNSAFE = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")


def _escaped(match: re.Match) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def xml_safe(text: str) -> str:
    """`text` with every character that XML 1.0 forbids (and DEL, C1 controls, lone surrogates) written as a
    visible escape (\\x00, \\udc80); newlines, tabs and everything printable kept."""
    return _UNSAFE.sub(_escaped, text)


def foreign(text: str | bytes, limit: int = FOREIGN_LIMIT, keep: str = "head") -> str:
    """`text` (bytes are read as UTF-8, a malformed byte as U+FFFD) made safe (xml_safe) and cut to at most
    `limit` characters, keeping its start (`keep="head"`: a version, a reason) or its end ("tail": a call's
    last output), with a note of how much was cut. Applied twice, it changes nothing more."""
    if isinstance(text, bytes):
        text = text.decode("utf-8", errors="replace")
    text = xml_safe(str(text))
    if len(text) <= limit:
        return text
    kept = limit - 40  # room for the note
    if keep == "head":
        return f"{text[:kept]} [... {len(text) - kept} more characters]"
    return f"[... {len(text) - kept} characters before] {text[-kept:]}"


#: Characters a one-line verdict keeps of foreign text (an engine's error, a line of a user's file).
LINE_LIMIT = 400


def one_line(text: str, limit: int = LINE_LIMIT) -> str:
    """`text` on one line (its lines joined by " | ", runs of blanks and unprintable characters dropped),
    bounded as `foreign` bounds it: a 1 MB tag name in Mitsuba's error must not reach a verdict whole."""
    lines = [" ".join(line.split()) for line in str(text).strip().splitlines()]
    joined = " | ".join(line for line in lines if line)
    return foreign("".join(c for c in joined if c.isprintable()), limit)
