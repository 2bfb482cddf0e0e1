"""The painted panel rows: every pixel of a picture is its own colour, scaled nearest-neighbour; the colour bars
span their maps end to end; the text is there."""
from __future__ import annotations

import io

import numpy as np
from matplotlib import colormaps
from PIL import Image

from harness.report.panels import Bar, Panel, row_png


def _decode(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def test_a_picture_keeps_its_pixels_scaled_by_a_whole_factor():
    rng = np.random.default_rng(3)
    pixels = rng.integers(0, 256, (16, 16, 3)).astype(np.float64) / 255.0
    canvas = _decode(row_png([Panel(pixels, "a title")], size=64))
    # The picture's 4x4 blocks are found somewhere in the canvas: look for its top-left block.
    expected = np.repeat(np.repeat((pixels * 255 + 0.5).astype(np.uint8), 4, axis=0), 4, axis=1)
    hits = np.argwhere(np.all(canvas == expected[0, 0], axis=-1))
    assert any(np.array_equal(canvas[y:y + 64, x:x + 64], expected) for y, x in hits)


def test_a_colour_bar_runs_from_the_top_colour_to_the_bottom_colour():
    bar = Bar("viridis", -2.0, 2.0, "label")
    canvas = _decode(row_png([Panel(bar.colour(np.zeros((8, 8))), "t", bar)], size=100))
    top, bottom = (np.round(np.asarray(colormaps["viridis"](v)[:3]) * 255).astype(int) for v in (1.0, 0.0))
    flat = canvas.reshape(-1, 3).astype(int)
    assert (np.abs(flat - top).max(axis=1) <= 1).any() and (np.abs(flat - bottom).max(axis=1) <= 1).any()


def test_values_outside_the_bar_take_its_end_colours():
    bar = Bar("RdBu_r", -1.0, 1.0)
    ends = bar.colour(np.array([[-5.0, -1.0, 1.0, 7.0]]))
    np.testing.assert_array_equal(ends[0, 0], ends[0, 1])
    np.testing.assert_array_equal(ends[0, 2], ends[0, 3])
    assert not np.array_equal(ends[0, 0], ends[0, 3])


def test_text_is_drawn_and_a_wide_title_widens_its_panel():
    plain = _decode(row_png([Panel(np.ones((8, 8, 3)), "")], size=32))
    titled = _decode(row_png([Panel(np.ones((8, 8, 3)), "a title much wider than the picture itself")], size=32))
    assert titled.shape[1] > plain.shape[1]
    assert (titled < 128).any()  # ink


def test_axes_and_a_row_title_add_room_and_ink():
    square = np.full((10, 10, 3), 0.5)
    bare = _decode(row_png([Panel(square, "t")], size=50))
    framed = _decode(row_png([Panel(square, "t", axes=("x label", "y label"))], size=50, title="row"))
    assert framed.shape[0] > bare.shape[0] and framed.shape[1] > bare.shape[1]
