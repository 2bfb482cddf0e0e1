"""A Nori scene file rendered by our renderer through the translation (harness/engines/nori/to_mitsuba.py) and
compared with the image Nori itself rendered of it, where Nori ships one: the check that the translation
reads the camera, transforms, meshes and lights as Nori does. Not a test: Nori's scenes and images stay in
Nori's repository (for example its scenes/pa1/bunny.xml with gh-pages references/bunny.exr, or
scenes/pa3/sphere/sphere_ao.xml with its ref/sphere_ao.exr at commit 425187e).

    .venv/bin/python -m tools.nori_reference SCENE.xml NORI.exr [--abs] [--spp 16]

--abs compares |mcval's| (Nori's tutorial normals integrator writes |n|). Prints both image means, the mean and
largest difference of 16 x 16-pixel block means, and the same for our image mirrored left to right (a
handedness check: it must be far larger)."""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from harness.engines.nori.to_mitsuba import nori_to_mitsuba
from harness.engines.scene_paths import absolute_paths
from harness.exr import read_image

BLOCK = 16


def block_means(image: np.ndarray) -> np.ndarray:
    h, w = (s - s % BLOCK for s in image.shape[:2])
    return image[:h, :w].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, -1).mean(axis=(1, 3))


def main(argv: list[str] | None = None) -> int:
    q = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    q.add_argument("scene", type=Path)
    q.add_argument("reference", type=Path)
    q.add_argument("--abs", action="store_true", help="compare |mcval's| (Nori's normals integrator writes |n|)")
    q.add_argument("--spp", type=int, default=16)
    args = q.parse_args(argv)
    root = nori_to_mitsuba(args.scene.read_text(), args.scene)
    for e in root.iter("integer"):
        if e.get("name") == "sample_count":
            e.set("value", str(args.spp))
    absolute_paths(root, args.scene)  # its meshes named as Nori finds them, so the copy can live anywhere
    with tempfile.TemporaryDirectory() as tmp:
        mitsuba = Path(tmp) / "scene.xml"
        mitsuba.write_text(ET.tostring(root, encoding="unicode"))
        render = Path(sys.executable).parent / "render"
        subprocess.run([str(render), str(mitsuba), "-o", f"{tmp}/mcval.exr", "-q"], check=True)
        mcval, _ = read_image(Path(tmp) / "mcval.exr")
    theirs, _ = read_image(args.reference)
    mcval = np.abs(mcval) if args.abs else mcval
    print(f"image mean: mcval {mcval.mean():.6g}, Nori's {theirs.mean():.6g}")
    for label, image in (("as rendered", mcval), ("mirrored", mcval[:, ::-1])):
        d = np.abs(block_means(image) - block_means(theirs))
        print(f"{label}: block means differ by {d.mean():.3g} on average, {d.max():.3g} at most")
    return 0


if __name__ == "__main__":
    sys.exit(main())
