"""Dot products and lengths over the last axis of (..., 3) arrays, written out per component: numpy's reductions
over a last axis of 3 cost several times more on the analytic engine's large arrays, and sum in the same
order (x + y, then + z)."""
from __future__ import annotations

import numpy as np


def dot(a: np.ndarray, b: np.ndarray, keepdims: bool = False) -> np.ndarray:
    """sum(a * b, axis=-1) for (..., 3) arrays (either may be one vector)."""
    out = a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]
    return out[..., None] if keepdims else out


def norm(a: np.ndarray, keepdims: bool = False) -> np.ndarray:
    """The length of each (..., 3) vector."""
    return np.sqrt(dot(a, a, keepdims))
