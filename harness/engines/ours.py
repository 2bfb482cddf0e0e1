"""Our renderer, through its Python module `mcrender` (built by CMake, see the Makefile)."""
from __future__ import annotations

import numpy as np

from harness.engines.base import Engine, WarpFunctions


def _load_module():
    try:
        import mcrender
    except ImportError as e:
        raise RuntimeError("the renderer's Python module `mcrender` is not built or not on the path: "
                           "run `make build` (it builds it into build/python)") from e
    return mcrender


class OurEngine(Engine):
    """The C++ renderer under test."""

    name = "mcval"

    def __init__(self) -> None:
        self._m = _load_module()

    def version(self) -> str:
        return "mcrender (this repository)"

    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        sample_fn = getattr(self._m, name, None)
        pdf_fn = getattr(self._m, name + "_pdf", None)
        if sample_fn is None or pdf_fn is None:
            return None
        extra = () if alpha is None else (float(alpha),)

        def sample(u: np.ndarray) -> np.ndarray:
            return sample_fn(np.ascontiguousarray(u, dtype=np.float32), *extra).astype(np.float64)

        def pdf(p: np.ndarray) -> np.ndarray:
            return pdf_fn(np.ascontiguousarray(p, dtype=np.float32), *extra).astype(np.float64)

        def native_run(n: int):
            u = np.random.default_rng(1).random((n, 2), dtype=np.float32)
            return lambda: sample_fn(u, *extra)

        return WarpFunctions(sample, pdf, native_run)
