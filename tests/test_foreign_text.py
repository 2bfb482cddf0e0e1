"""Foreign text (a renderer's version, output or message) is bounded and holds nothing that JSON written as
UTF-8, an HTML page or XML 1.0 cannot carry."""
import json
import xml.etree.ElementTree as ET

from harness.foreign_text import FOREIGN_LIMIT, foreign, xml_safe

DIRTY = "a\x00b\x01\x1b[31m\x7f\x85\ud800\udfff\ufffe end\tok\n"


def test_forbidden_characters_become_visible_escapes():
    assert xml_safe(DIRTY) == "a\\x00b\\x01\\x1b[31m\\x7f\\x85\\ud800\\udfff\\ufffe end\tok\n"
    assert xml_safe("plain é ü 漢 \n\t") == "plain é ü 漢 \n\t"


def test_cleaned_text_goes_into_xml_and_utf8_json():
    text = foreign(DIRTY.encode("utf-8", "surrogatepass") + b"\xff\xfe" + DIRTY.encode("utf-8", "surrogatepass"))
    ET.fromstring(f"<a b='{text}'>{text}</a>".encode())  # parses
    json.dumps(text, ensure_ascii=False).encode("utf-8")  # no lone surrogate left
    assert "\ufffd" in text  # the malformed bytes


def test_long_text_is_cut_at_its_head_or_tail():
    text = "x" * 10 + "y" * (10 * FOREIGN_LIMIT)
    head, tail = foreign(text), foreign(text, keep="tail")
    assert head.startswith("xxx") and head.endswith(" more characters]")
    assert tail.startswith("[... ") and "characters before]" in tail and "x" not in tail
    assert head.endswith(f"[... {len(text) - FOREIGN_LIMIT + 40} more characters]")
    assert len(head) <= FOREIGN_LIMIT and len(tail) <= FOREIGN_LIMIT and foreign("short") == "short"


def test_cutting_twice_changes_nothing_more():
    for keep in ("head", "tail"):
        once = foreign("\x00" * FOREIGN_LIMIT + "y" * FOREIGN_LIMIT, keep=keep)
        assert len(once) <= FOREIGN_LIMIT and foreign(once, keep=keep) == once


def test_one_line_joins_lines_drops_controls_and_bounds():
    from harness.foreign_text import LINE_LIMIT, one_line
    assert one_line("  first   line\n\n second\x07 line \n") == "first line | second line"
    long = one_line("<" + "a" * 1_000_000 + ">")
    assert len(long) <= LINE_LIMIT and "more characters" in long
