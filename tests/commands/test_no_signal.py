"""Images without signal are INCONCLUSIVE, never PASS and never "not independent": a camera that sees a
one-sided floor from behind (both images 0) and a speck of a sphere at 32 pixels (a bias of 5 % cannot be
found); each says what would decide it, and a run of nothing but such cases judged nothing (exit status 3)."""
import json
import xml.etree.ElementTree as ET

from harness.cli import main
from harness.images.suite import SCENES_DIR

FLOOR = """    <shape type="rectangle">
        <transform name="to_world">
            <scale value="100"/>
            <rotate x="1" angle="-90"/>
        </transform>
        <ref id="floor"/>
    </shape>"""
SPECK = """    <shape type="sphere">
        <point name="center" value="0, 0, 0"/>
        <float name="radius" value="0.03"/>
        <ref id="floor"/>
    </shape>"""
CAMERA = '<lookat origin="0, 3, 3" target="0, 0, 0" up="0, 1, 0"/>'


def test_images_without_signal_are_inconclusive_and_a_run_of_them_fails(tmp_path, capsys):
    source = (SCENES_DIR / "plane_point.xml").read_text()
    assert FLOOR in source and CAMERA in source
    folder = tmp_path / "scenes"
    folder.mkdir()
    (folder / "from_behind.xml").write_text(source.replace(CAMERA, CAMERA.replace("0, 3, 3", "0, -3, 3")))
    (folder / "speck.xml").write_text(source.replace(FLOOR, SPECK))
    out = tmp_path / "results"
    assert main(["images", "--scene", str(folder), "--only", "ao", "--resolution", "32", "--out", str(out)]) == 3
    cases = {c["scene"]: c for c in json.loads((out / "latest" / "results.json").read_text())["images"]}
    assert {c["verdict"] for c in cases.values()} == {"INCONCLUSIVE"}
    assert not any(c["pass"] for c in cases.values())
    assert cases["from_behind"]["inconclusive"].startswith("no signal: both images are 0 everywhere")
    assert "above the 5% it must resolve" in cases["speck"]["inconclusive"]
    assert "spp" in cases["speck"]["inconclusive"]  # what would decide it, or why no budget of mcval's would
    for case in cases.values():
        assert all(test["independence"]["pass"] for test in case["tests"].values())
    skipped = list(ET.parse(out / "latest" / "junit.xml").iter("skipped"))
    assert len(skipped) == 2 and all(s.get("message").startswith("INCONCLUSIVE: ") for s in skipped)
    printed = " ".join(capsys.readouterr().out.split())
    assert "FAIL nothing was judged: image cases: 2 inconclusive (from_behind:ao, speck:ao)" in printed
