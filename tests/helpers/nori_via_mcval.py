"""A stand-in for a student's Nori build, for the tests: it reads the Nori scene the harness wrote (through
harness/engines/nori/to_mitsuba.py, the other direction) and renders it with our renderer. With
`--bug fov` its field of view is 5 % too wide, a planted camera defect the comparison must catch; with
`--bug radiance` its area lights are 5 % too bright.

usage: nori_via_mcval.py SCENE OUTPUT SEED [--bug fov|radiance]"""
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from harness.engines.nori.to_mitsuba import nori_to_mitsuba  # noqa: E402


def main(scene: str, output: str, seed: str, *bug: str) -> int:
    root = nori_to_mitsuba(Path(scene).read_text(), Path(scene))
    if bug == ("--bug", "fov"):
        fov = next(e for e in root.iter("float") if e.get("name") == "fov")
        fov.set("value", str(1.05 * float(fov.get("value"))))
    if bug == ("--bug", "radiance"):
        for e in root.iter("emitter"):
            radiance = next(c for c in e if c.get("name") == "radiance")
            radiance.set("value", ", ".join(str(1.05 * float(v)) for v in radiance.get("value").split(",")))
    mitsuba = Path("mitsuba.xml").resolve()
    # Nori resolves mesh files against the scene's folder; the copy lives elsewhere, so name them absolutely.
    for e in root.iter("string"):
        if e.get("name") == "filename" and not Path(e.get("value")).is_absolute():
            e.set("value", str(Path(scene).parent / e.get("value")))
    mitsuba.write_text(ET.tostring(root, encoding="unicode"))
    render = Path(sys.executable).parent / "render"
    return subprocess.call([str(render), str(mitsuba), "-o", output, "--seed", seed, "-q", "--threads", "1"])


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
