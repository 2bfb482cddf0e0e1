"""junit.xml parses whatever an engine said: its meta (version) and a case's failure may hold characters XML
1.0 forbids, lone surrogates among them, and write_atomic writes them as escapes."""
import xml.etree.ElementTree as ET

from harness.images.evaluate import failure as failed_verdict
from harness.images.result import ImageResult
from harness.images.suite import ImageCase
from harness.report.junit import junit_xml
from harness.results import write_atomic

DIRTY = "v\x00\x01\x1b[0m\x7f\x9f\ud800\udc80\ufffe end"


def test_junit_xml_parses_with_forbidden_characters(tmp_path):
    failed = ImageResult(case=ImageCase("plane_ao", "ao"), decision=failed_verdict(f"render: {DIRTY}", DIRTY))
    path = write_atomic(tmp_path / "junit.xml", junit_xml([failed], None, {"engine": DIRTY, DIRTY: "key"}))
    tree = ET.parse(path)
    failure = next(tree.iter("failure"))
    escaped = "v\\x00\\x01\\x1b[0m\\x7f\\x9f\\ud800\\udc80\\ufffe end"
    assert failure.get("message") == f"render: {escaped}" and failure.text.endswith(escaped)
    assert {p.get("name"): p.get("value") for p in tree.iter("property")} == {"engine": escaped, escaped: "key"}
