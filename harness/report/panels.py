"""A row of picture panels painted straight into pixels with Pillow: each panel an image under its title, with a
colour bar after it and axis labels where given, the row under an optional title.

The reports paint dozens of these rows a run. Through matplotlib each panel and bar was an axes object with its
ticks, built and drawn every time: a fifth of `validate`. The rows have a fixed layout, so here the layout is
arithmetic and the pixels are the images' own, scaled nearest-neighbour as the figures showed them.
"""
from __future__ import annotations

import io
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import matplotlib
import numpy as np
from matplotlib import colormaps, ticker
from PIL import Image, ImageDraw, ImageFont

#: A picture is at most this much wider than high (a wide image is shown less high).
MAX_ASPECT = 1.6
_MARGIN, _GAP, _STRIP = 8, 14, 12
_INK, _PAPER = (0, 0, 0), (255, 255, 255)


@dataclass(frozen=True)
class Bar:
    """A colour map over [vmin, vmax] (values outside take its end colours), drawn as a bar with ticks."""

    cmap: str
    vmin: float
    vmax: float
    label: str = ""

    def colour(self, data: np.ndarray) -> np.ndarray:
        """(H, W) values as (H, W, 3) colours in [0, 1]; NaN as black."""
        span = self.vmax - self.vmin
        x = np.clip((np.asarray(data, np.float64) - self.vmin) / (span if span > 0 else 1.0), 0.0, 1.0)
        return np.nan_to_num(colormaps[self.cmap](x)[..., :3])


@dataclass(frozen=True)
class Panel:
    """(H, W, 3) colours in [0, 1], row 0 at the top. `bar`: the colour bar drawn after the panel. `axes`:
    (x label, y label) of a unit parameter square, with ticks at 0, 0.5 and 1 (row 0 is y = 1)."""

    pixels: np.ndarray
    title: str
    bar: Bar | None = None
    axes: tuple[str, str] | None = None


@cache
def _font(size: int) -> ImageFont.FreeTypeFont:
    # DejaVu Sans, as matplotlib's default: it ships inside matplotlib, so no system font is needed.
    return ImageFont.truetype(str(Path(matplotlib.get_data_path()) / "fonts" / "ttf" / "DejaVuSans.ttf"), size)


def _label(value: float) -> str:
    text = f"{value:.6g}".replace("-", "\u2212")
    return "0" if text in ("\u22120", "0") else text


def _ticks(bar: Bar) -> list[float]:
    values = ticker.MaxNLocator(nbins=5).tick_values(bar.vmin, bar.vmax)
    slack = 1e-9 * (abs(bar.vmax - bar.vmin) or 1.0)
    return [float(v) for v in values if bar.vmin - slack <= v <= bar.vmax + slack]


def _width(text: str, font: ImageFont.FreeTypeFont) -> int:
    return int(np.ceil(font.getlength(text)))


def _upright(draw_on: Image.Image, text: str, font: ImageFont.FreeTypeFont, centre: tuple[int, int]) -> None:
    """`text` turned a quarter anticlockwise (reading upwards), centred at `centre`."""
    box = Image.new("RGB", (_width(text, font) + 2, font.size + 4), _PAPER)
    ImageDraw.Draw(box).text((1, 0), text, font=font, fill=_INK)
    turned = box.rotate(90, expand=True)
    draw_on.paste(turned, (centre[0] - turned.width // 2, centre[1] - turned.height // 2))


def _picture_size(pixels: np.ndarray, size: int) -> tuple[int, int]:
    h, w = pixels.shape[:2]
    scale = min(size / h, size * MAX_ASPECT / w)
    return max(1, round(w * scale)), max(1, round(h * scale))


def _bar_width(bar: Bar, small: ImageFont.FreeTypeFont) -> int:
    ticks = max((_width(_label(v), small) for v in _ticks(bar)), default=0)
    return _STRIP + 4 + ticks + (small.size + 8 if bar.label else 0)


def _axes_room(panel: Panel, small: ImageFont.FreeTypeFont) -> int:
    return small.size + 8 + _width("0.5", small) + 4 if panel.axes else 0


def row_png(panels: list[Panel], size: int = 176, title: str | None = None) -> bytes:
    """The row as PNG bytes: each picture fitted into `size` pixels high (MAX_ASPECT times as wide)."""
    font, small = _font(12), _font(10)
    line = font.size + 6
    top = _MARGIN + (line + 2 if title else 0) + line
    pictures = [_picture_size(p.pixels, size) for p in panels]
    height = max(h for _, h in pictures)
    bottom = 2 * (small.size + 6) + _MARGIN if any(p.axes for p in panels) else _MARGIN
    lefts, x = [], _MARGIN
    for p, (w, _) in zip(panels, pictures):
        pad = max(0, _width(p.title, font) - w) // 2  # a title wider than its picture
        x += max(pad, _axes_room(p, small))
        lefts.append(x)
        x += w + max(pad, _GAP // 2 + _bar_width(p.bar, small) if p.bar else 0) + _GAP
    canvas = Image.new("RGB", (x - _GAP + _MARGIN, top + height + bottom), _PAPER)
    draw = ImageDraw.Draw(canvas)
    if title:
        draw.text((canvas.width // 2, _MARGIN), title, font=font, fill=_INK, anchor="mt")
    for p, (w, h), left in zip(panels, pictures, lefts):
        y = top + (height - h) // 2
        shown = np.clip(np.asarray(p.pixels, np.float64) * 255.0 + 0.5, 0, 255).astype(np.uint8)
        canvas.paste(Image.fromarray(shown, "RGB").resize((w, h), Image.NEAREST), (left, y))
        draw.text((left + w // 2, top - line + 2), p.title, font=font, fill=_INK, anchor="mt")
        if p.axes:
            _draw_axes(canvas, draw, p.axes, (left, y, w, h), small)
        if p.bar:
            _draw_bar(canvas, draw, p.bar, (left + w + _GAP // 2, y, h), small)
    buf = io.BytesIO()
    canvas.save(buf, format="PNG", compress_level=1)  # a report of many pictures: speed over a few percent of size
    return buf.getvalue()


def _draw_axes(canvas: Image.Image, draw: ImageDraw.ImageDraw, labels: tuple[str, str],
               box: tuple[int, int, int, int], small: ImageFont.FreeTypeFont) -> None:
    left, y, w, h = box
    draw.rectangle((left - 1, y - 1, left + w, y + h), outline=_INK)
    for f in (0.0, 0.5, 1.0):
        px, py = left + round(f * (w - 1)), y + h - 1 - round(f * (h - 1))
        draw.line((px, y + h, px, y + h + 3), fill=_INK)
        draw.text((px, y + h + 4), f"{f:g}", font=small, fill=_INK, anchor="mt")
        draw.line((left - 4, py, left - 1, py), fill=_INK)
        draw.text((left - 6, py), f"{f:g}", font=small, fill=_INK, anchor="rm")
    draw.text((left + w // 2, y + h + small.size + 10), labels[0], font=small, fill=_INK, anchor="mt")
    _upright(canvas, labels[1], small, (left - _width("0.5", small) - small.size // 2 - 10, y + h // 2))


def _draw_bar(canvas: Image.Image, draw: ImageDraw.ImageDraw, bar: Bar, at: tuple[int, int, int],
              small: ImageFont.FreeTypeFont) -> None:
    """The bar over 80 % of the picture's height `at[2]`, its ticks and label to the right."""
    x, y, h = at[0], at[1] + at[2] // 10, max(2, round(0.8 * at[2]))
    ramp = bar.colour(np.linspace(bar.vmax, bar.vmin, h)[:, None].repeat(_STRIP, axis=1))
    canvas.paste(Image.fromarray((ramp * 255 + 0.5).astype(np.uint8), "RGB"), (x, y))
    draw.rectangle((x - 1, y - 1, x + _STRIP, y + h), outline=_INK)
    span = bar.vmax - bar.vmin
    widest = 0
    for v in _ticks(bar):
        ty = y + round((bar.vmax - v) / span * (h - 1)) if span > 0 else y + h // 2
        draw.line((x + _STRIP, ty, x + _STRIP + 3, ty), fill=_INK)
        draw.text((x + _STRIP + 5, ty), _label(v), font=small, fill=_INK, anchor="lm")
        widest = max(widest, _width(_label(v), small))
    if bar.label:
        _upright(canvas, bar.label, small, (x + _STRIP + 8 + widest + small.size // 2, y + h // 2))
