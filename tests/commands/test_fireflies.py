"""A renderer that writes a firefly into one pixel (of one batch, or of four) fails through an engine file,
whatever the firefly's size, and says so in its first line; the reports carry the verdict."""
import json
import xml.etree.ElementTree as ET

import pytest

from harness.cli import main
from tests.helpers.foreign_renderers import write_engine


@pytest.mark.parametrize("seed, factor, batches", [(0, 10.0, 1), (1, 1e4, 4), (2, 3e38, 1)])
def test_a_firefly_fails_through_an_engine_file(tmp_path, capsys, seed, factor, batches):
    engine = write_engine(tmp_path, "firefly", constants={"FACTOR": factor, "BATCHES": batches})
    out = tmp_path / "results"
    assert main(["images", "--engine", str(engine), "--only", "plane_point:simple", "--seed", str(seed),
                 "--out", str(out)]) == 1
    (case,) = json.loads((out / "latest" / "results.json").read_text())["images"]
    assert case["verdict"] == "FAIL"
    failure = next(ET.parse(out / "latest" / "junit.xml").iter("failure"))
    first = failure.get("message")
    assert "firefly" in first and "(row 64, column 64" in first, first
