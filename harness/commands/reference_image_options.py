"""--reference-image, --reference-spp, --reference-noise: one image from elsewhere as the reference of one
case (harness/images/reference_image.py)."""
from __future__ import annotations

import argparse
from pathlib import Path


def add_reference_image_options(q: argparse.ArgumentParser) -> None:
    from harness.images.reference_image import NOISE_MODELS

    q.add_argument("--reference-image", type=Path, metavar="FILE.exr",
                   help="compare the one --scene file's case with this image (e.g. Nori's ref/*.exr) instead of "
                        "Mitsuba's render; the scene is rendered at the image's size")
    q.add_argument("--reference-spp", type=int, metavar="N",
                   help="with --reference-image: the samples per pixel the image was rendered with")
    q.add_argument("--reference-noise", choices=NOISE_MODELS, default="stated",
                   help="with --reference-image, the image's variance: 'stated' (default), the test engine's "
                        "per-sample variance over N samples, and a FAIL if the image's noise does not fit N; "
                        "'measured', that variance scaled to the noise the image shows")


def check_reference_image(args: argparse.Namespace) -> None:
    """ValueError for --reference-image without what it needs: one --scene file and --reference-spp."""
    image = getattr(args, "reference_image", None)
    if image is None:
        if getattr(args, "reference_spp", None) is not None:
            raise ValueError("--reference-spp is for --reference-image")
        return
    if not args.scene or len(args.scene) != 1 or not args.scene[0].is_file():
        raise ValueError("--reference-image needs exactly one --scene file: the scene the image shows")
    if args.reference_spp is None or args.reference_spp < 1:
        raise ValueError("--reference-image needs --reference-spp N (N >= 1): the samples per pixel of the image")
    if not image.is_file():
        raise ValueError(f"--reference-image {image}: no such file")


def chosen_image_case(args: argparse.Namespace, cases: list) -> list:
    """With --reference-image, the one case the image is the render of: the only one selected, or the one whose
    integrator the file itself names; the cases as they are otherwise. ValueError when neither says which."""
    if getattr(args, "reference_image", None) is None:
        return cases
    own = [c for c in cases if c.integrator == _file_integrator(c.path)]
    if len(cases) > 1 and len(own) == 1:  # the file names one of mcval's (a Nori file's, as translated)
        return own
    if len(cases) != 1:
        keys = ", ".join(c.key for c in cases) or "none"
        raise ValueError(f"--reference-image: the image is one integrator's render; choose its case with --only "
                         f"(this scene's cases: {keys})")
    return cases


def _file_integrator(path: Path) -> str | None:
    """The type of the scene file's top-level <integrator>, or None."""
    import xml.etree.ElementTree as ET

    try:
        node = ET.parse(path).getroot().find("integrator")
    except (ET.ParseError, OSError):
        return None
    return None if node is None else node.get("type")


def reference_image(args: argparse.Namespace):
    """The ReferenceImage of the run, or None."""
    if getattr(args, "reference_image", None) is None:
        return None
    from harness.images.reference_image import ReferenceImage
    return ReferenceImage(args.reference_image.resolve(), args.reference_spp, args.reference_noise)
