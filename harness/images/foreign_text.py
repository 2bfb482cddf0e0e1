"""Text that comes from outside the harness (an engine's error, a line of a user's file) made fit to print and
store: one line, at most MAX_LINE characters. A 1 MB tag name in Mitsuba's error would otherwise go whole into
results.json, the report and the terminal (whose highlighter takes minutes over it)."""
from __future__ import annotations

#: The most characters of foreign text a verdict line keeps.
MAX_LINE = 400


def bounded(text: str, limit: int = MAX_LINE) -> str:
    """`text` cut to `limit` characters, saying how much was left out."""
    if len(text) <= limit:
        return text
    return f"{text[:limit]} ... ({len(text) - limit} more characters)"


def one_line(text: str, limit: int = MAX_LINE) -> str:
    """`text` on one line (its lines joined by " | ", control characters dropped), bounded."""
    lines = [" ".join(line.split()) for line in text.strip().splitlines()]
    joined = " | ".join(line for line in lines if line)
    return bounded("".join(c for c in joined if c.isprintable()), limit)
