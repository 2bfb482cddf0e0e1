"""OpenEXR files in and out of the harness, through OpenImageIO.

A file is a set of RGB layers: "RGB" for the channels R, G, B and "<name>" for <name>.R, .G, .B (as the
renderer writes `batch<k>` and `variance`), plus its header attributes.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np


#: Channels a render's file may hold: 3 x (1363 batches + mean + variance), below the 4096 that
#: OpenImageIO's EXR reader takes at most (renderer/scene_limits.h).
MAX_CHANNELS = 3 * (1363 + 2)


class ExrError(ValueError):
    """A file OpenImageIO cannot read as an EXR, or one that lacks what was asked of it."""


def _read(path: Path, check=None) -> tuple[np.ndarray, list[str], dict[str, object]]:
    """(H, W, C) float32 pixels, channel names and attributes of the image at `path`; `check(input, spec)`
    may refuse the file (ExrError) before its pixels are read."""
    import OpenImageIO as oiio

    # The renderer writes 3 channels per batch plus mean and variance (up to 1363 batches): above OIIO's
    # default guard of 1024 channels, which is there against corrupt headers.
    oiio.attribute("limits:channels", MAX_CHANNELS)
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise ExrError(oiio.geterror().strip() or f"cannot open {path}")
    try:
        spec = inp.spec()
        if check is not None:
            check(inp, spec)
        pixels = inp.read_image(0, 0, 0, spec.nchannels, "float")
        if pixels is None:
            raise ExrError(inp.geterror() or "cannot read its pixels")
        attributes = {a.name: a.value for a in spec.extra_attribs}
    finally:
        inp.close()
    pixels = np.asarray(pixels, np.float32).reshape(spec.height, spec.width, spec.nchannels)
    return pixels, list(spec.channelnames), attributes


def read_layers(path: Path) -> tuple[dict[str, np.ndarray], dict[str, object]]:
    """The file's RGB layers as (H, W, 3) float32 arrays (half files converted), and its attributes."""
    pixels, names, attributes = _read(path)
    index = {name: i for i, name in enumerate(names)}
    layers = {}
    for name in {n.rsplit(".", 1)[0] if "." in n else "RGB" for n in names}:
        prefix = "" if name == "RGB" else name + "."
        channels = [index.get(prefix + c) for c in "RGB"]
        if None not in channels:
            layers[name] = np.ascontiguousarray(pixels[..., channels])
    return layers, attributes


def write_layers(path: Path, layers: dict[str, np.ndarray]) -> None:
    """RGB layers (H, W, 3) as one float32, ZIP-compressed, scanline EXR at `path`."""
    import OpenImageIO as oiio

    shape = next(iter(layers.values())).shape
    names = [f"{'' if n == 'RGB' else n + '.'}{c}" for n in layers for c in "RGB"]
    spec = oiio.ImageSpec(shape[1], shape[0], len(names), "float")
    spec.channelnames = tuple(names)
    spec.attribute("compression", "zip")
    pixels = np.concatenate([np.asarray(v, np.float32) for v in layers.values()], axis=-1)
    out = oiio.ImageOutput.create(str(path))
    if out is None or not out.open(str(path), spec):
        raise ExrError(oiio.geterror() or (out.geterror() if out else f"cannot write {path}"))
    try:
        if not out.write_image(np.ascontiguousarray(pixels)):
            raise ExrError(out.geterror())
    finally:
        out.close()


def _rgb_channels(names: list[str]) -> list[int] | None:
    """Indices of the channels that make one RGB image: R, G, B; else one layer's *.R, *.G, *.B; else Y (three
    times); None if there are none of these."""
    index = {name: i for i, name in enumerate(names)}
    if all(c in index for c in "RGB"):
        return [index[c] for c in "RGB"]
    layers = sorted({n.rsplit(".", 1)[0] for n in names if "." in n})
    for layer in layers:
        if all(f"{layer}.{c}" in index for c in "RGB"):
            return [index[f"{layer}.{c}"] for c in "RGB"]
    for luminance in ("Y", *(f"{layer}.Y" for layer in layers)):
        if luminance in index:
            return [index[luminance]] * 3
    return None


def read_image(path: Path) -> tuple[np.ndarray, dict[str, object]]:
    """One RGB image of any EXR a renderer may write: R, G, B (or one layer's), or Y, half or float; as an
    (H, W, 3) float32 array, with the file's attributes. ExrError saying what the file holds otherwise."""

    def check(inp, spec) -> None:
        if inp.format_name() != "openexr":
            raise ExrError(f"is a {inp.format_name()} file, not an EXR")
        if _rgb_channels(list(spec.channelnames)) is None:
            raise ExrError(f"has no R, G, B or Y channels (it has {', '.join(spec.channelnames[:8]) or 'none'})")

    pixels, names, attributes = _read(path, check)
    return np.ascontiguousarray(pixels[..., _rgb_channels(names)]), attributes
