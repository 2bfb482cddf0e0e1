"""What a failed comparison with a single image looks like: the simple differences between two renders of one
scene that decide a verdict and that a user cannot see in a p-value.

- background: the image is lit where the tested image is black (or the reverse) on a share of the frame: an environment
  shown to camera rays in one and hidden in the other (`hide_emitters`);
- zoom: the image matches the tested image scaled about the centre of the frame (a field of view or a look-at that
  differs), and by how much;
- shift: the image matches the tested image moved by a fraction of a pixel or more (a pixel-centre convention);
- scale: the image is the tested image times a constant (a missing or extra factor), once zoom and shift are taken out.

Each is a least-squares fit of the tested image, transformed, to the image on the inner part of the frame, both blurred
(the noise of a single image would swamp the fit); a transform is reported when it removes at least half of
the squared difference that no transform leaves.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import affine_transform, gaussian_filter

#: Zooms tried, about the centre of the frame (1.03: a 3 % change of the field of view).
ZOOMS = np.linspace(0.97, 1.03, 61)
#: Shifts tried along each axis, in pixels.
SHIFTS = np.linspace(-1.0, 1.0, 9)
#: The border left out of every fit, as a fraction of the frame (where a zoom brings in what is outside).
BORDER = 0.05
#: Standard deviation, in pixels, of the blur both images get before the fits.
BLUR = 1.5
#: A transform is reported when it leaves at most this fraction of the squared difference.
EXPLAINED = 0.5
#: The share of the frame that must be black on one side and lit on the other for a background finding.
BACKGROUND_SHARE = 0.02


def _moved(image: np.ndarray, zoom: float, dy: float, dx: float) -> np.ndarray:
    """`image` scaled by `zoom` about its centre and moved by (dy, dx) pixels (bilinear), channel by channel."""
    h, w = image.shape[:2]
    centre = np.array([(h - 1) / 2.0, (w - 1) / 2.0])
    matrix = np.eye(2) / zoom
    offset = centre - matrix @ (centre + np.array([dy, dx]))
    return np.stack([affine_transform(image[..., c], matrix, offset, order=1, mode="nearest")
                     for c in range(image.shape[-1])], axis=-1)


def _inner(h: int, w: int) -> tuple[slice, slice]:
    by, bx = max(1, int(BORDER * h)), max(1, int(BORDER * w))
    return slice(by, h - by), slice(bx, w - bx)


def diagnose(tested: np.ndarray, image: np.ndarray) -> str | None:
    """One line on what makes `image` differ from `tested` (two (H, W, 3) mean images), or None if no simple
    difference explains it."""
    tested, image = np.asarray(tested, np.float64), np.asarray(image, np.float64)
    found = []
    black_tested = np.all(tested == 0, axis=-1) & np.any(image > 0, axis=-1)
    black_image = np.all(image == 0, axis=-1) & np.any(tested > 0, axis=-1)
    for share, dark, lit in ((black_tested.mean(), "the tested image", "the image"),
                             (black_image.mean(), "the image", "the tested image")):
        if share >= BACKGROUND_SHARE:
            found.append(f"{lit} is lit where {dark} is black on {100 * share:.0f} % of the frame (an environment "
                         "shown to camera rays in one and hidden in the other: hide_emitters)")
    if found:
        return "; ".join(found)
    # Both blurred first: the fit is about where the edges are, and a noisy image's noise would swamp it.
    tested, image = (gaussian_filter(x, (BLUR, BLUR, 0)) for x in (tested, image))
    inner = _inner(*tested.shape[:2])
    target = image[inner]

    def residual(zoom: float, dy: float = 0.0, dx: float = 0.0) -> tuple[float, float]:
        moved = _moved(tested, zoom, dy, dx)[inner] if (zoom, dy, dx) != (1.0, 0.0, 0.0) else tested[inner]
        norm = float(np.square(moved).sum())
        gain = float((moved * target).sum()) / norm if norm > 0 else 1.0
        return float(np.square(target - gain * moved).sum()), gain

    plain = float(np.square(target - tested[inner]).sum())
    if plain == 0:
        return None
    zoom = min(ZOOMS, key=lambda z: residual(z)[0])
    dy, dx = min(((y, x) for y in SHIFTS for x in SHIFTS), key=lambda s: residual(zoom, *s)[0])
    left, gain = residual(zoom, dy, dx)
    if left > EXPLAINED * plain:
        return None
    parts = []
    if abs(zoom - 1.0) > 1e-9:
        parts.append(f"zoomed by {zoom:.3f} about the centre (a field of view {1 / zoom:.3f} times the tested one)")
    if dy or dx:
        parts.append(f"moved by ({dx:+.2f}, {dy:+.2f}) pixels (x, y)")
    if abs(gain - 1.0) > 1e-3:
        parts.append(f"times {gain:.4f}")
    if not parts:
        return None
    return (f"the image matches the tested image {', '.join(parts)}: that leaves {100 * left / plain:.0f} % of the squared "
            "difference")
