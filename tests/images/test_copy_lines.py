"""Engines' errors about a prepared copy named in the lines of the file as given."""
from harness.images.copy_lines import name_lines

LINES = [0, 1, 5, 9, 12]


def test_mitsubas_parse_and_instantiation_errors_name_the_users_line():
    assert name_lines("[parser.cpp:451] Error while loading string (line 3, col 8): bad", "C.xml", "U.xml", LINES) \
        == "[parser.cpp:451] in U.xml:9: bad"
    assert name_lines("[parser.cpp:1718] At string (line 4, col 4): failed to instantiate", "C.xml", "U.xml",
                      LINES) == "[parser.cpp:1718] in U.xml:12: failed to instantiate"


def test_mcval_names_the_users_line_and_an_unknown_line_stays_the_copys():
    assert name_lines("error: /c/C.xml:2: <foo>: unexpected", "/c/C.xml", "U.xml", LINES) == \
        "error: U.xml:5: <foo>: unexpected"
    assert name_lines("error: /c/C.xml:40: x (line 40, col 1)", "/c/C.xml", "U.xml", LINES) == \
        "error: /c/C.xml:40: x (line 40, col 1)"
    assert name_lines("a: 3", "", "U.xml", LINES) == "a: 3"


def test_a_second_element_ours_names_in_the_copy_is_the_users_line_too():
    reason = "error: /c/C.xml:2: <bsdf>: reads the reflectance, given here as a <ref> at line 3; ..."
    assert name_lines(reason, "/c/C.xml", "U.xml", LINES) == \
        "error: U.xml:5: <bsdf>: reads the reflectance, given here as a <ref> at line 9; ..."
    # Only what is said of the copy: a line of another file (an <include>d one) stays as it is.
    other = "error: /c/part.xml:2: <bsdf>: given here as a <ref> at line 3"
    assert name_lines(other, "/c/C.xml", "U.xml", LINES) == other
    assert name_lines("error: /c/C.xml:2: <ref> at line 40", "/c/C.xml", "U.xml", LINES) == \
        "error: U.xml:5: <ref> at line 40"
