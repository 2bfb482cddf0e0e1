"""Vector arithmetic over the last axis of (..., 3) arrays, written out per component: numpy's reductions over a
last axis of 3, and its broadcasts of one vector against (..., 3), run three elements at a time and cost several
times more on the analytic engine's large arrays. Sums go in the same order (x + y, then + z). A vector is a
(..., 3) array or the list of its three components."""
from __future__ import annotations

import numpy as np


def parts(a) -> list:
    """The three components of a (..., 3) array (views), or the list as given."""
    return a if isinstance(a, list) else [a[..., 0], a[..., 1], a[..., 2]]


def sub(a, b) -> list:
    """a - b, as components (either may be one vector)."""
    return [x - y for x, y in zip(parts(a), parts(b))]


def dot(a, b, keepdims: bool = False) -> np.ndarray:
    """sum(a * b, axis=-1) for (..., 3) arrays (either may be one vector)."""
    a, b = parts(a), parts(b)
    out = a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    return out[..., None] if keepdims else out


def norm(a, keepdims: bool = False) -> np.ndarray:
    """The length of each (..., 3) vector."""
    return np.sqrt(dot(a, a, keepdims))


def times(c: np.ndarray, w: np.ndarray) -> np.ndarray:
    """c (3,) * w (..., 1) as (..., 3), one channel at a time (each channel contiguous)."""
    w = w[..., 0]
    return np.moveaxis(np.stack([c[0] * w, c[1] * w, c[2] * w]), 0, -1)
