"""Square blocks of an image, each as one row: the clusters that the batch-independence and variance tests sum
over (a pixel filter correlates neighbours; blocks of a few pixels are nearly independent of each other)."""
from __future__ import annotations

import numpy as np


def tile_blocks(x: np.ndarray, tile: int) -> np.ndarray:
    """(..., H, W, C) -> (..., T, tile * tile * C), the T tiles in row-major order, zeros past the image's edge
    (so that a sum over a row is the tile's sum of what it holds)."""
    *lead, h, w, c = x.shape
    th, tw = -(-h // tile), -(-w // tile)
    padded = x
    if (th * tile, tw * tile) != (h, w):
        padded = np.zeros((*lead, th * tile, tw * tile, c))
        padded[..., :h, :w, :] = x
    blocks = padded.reshape(*lead, th, tile, tw, tile, c)
    blocks = np.moveaxis(blocks, -4, -3)  # (..., th, tw, tile, tile, c)
    return blocks.reshape(*lead, th * tw, tile * tile * c)
