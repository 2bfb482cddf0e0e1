"""A C or C++ warp library as an engine of warps alone: the functions of include/mcval_warps.h, float32 and
interleaved, called through ctypes on numpy arrays (docs/engines.md#warps-in-c-or-c)."""
from __future__ import annotations

import ctypes
import hashlib
from pathlib import Path

import numpy as np

from harness.engines.base import Engine, WarpFunctions

#: Each warp of the ABI and the dimension of its points.
DIMENSIONS = {"square_to_uniform_square": 2, "square_to_tent": 2, "square_to_uniform_disk": 2,
              "square_to_uniform_sphere": 3, "square_to_uniform_hemisphere": 3, "square_to_cosine_hemisphere": 3,
              "square_to_beckmann": 3}
#: The warps that take a parameter (last, as a float).
WITH_ALPHA = ("square_to_beckmann",)


class WarpUnavailable(RuntimeError):
    """A warp the library cannot be checked on, with one line saying why (a sampler without its pdf)."""


def _float32(a: np.ndarray, columns: int) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(a, np.float32).reshape(-1, columns))


def _pointer(a: np.ndarray):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_float))


class WarpLibraryEngine(Engine):
    """The warps a shared library exports. Its throughput is reported, not judged: the floor is for ours."""

    throughput_judged = False
    #: A warp the library does not export is left out of the matrix, not failed.
    warps_optional = True

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path).resolve()
        if not self.path.is_file():
            raise ValueError(f"--warp-library {path}: no such file")
        try:
            self._lib = ctypes.CDLL(str(self.path))
        except OSError as e:
            raise ValueError(f"--warp-library {path}: cannot load it as a shared library ({e})") from None
        self.name = self.label = self.path.stem.removeprefix("lib")

    def __reduce__(self):
        return WarpLibraryEngine, (self.path,)

    def exported(self) -> list[str]:
        """The warps of the ABI whose sampler the library exports."""
        return [name for name in DIMENSIONS if hasattr(self._lib, name)]

    def version(self) -> str:
        digest = hashlib.sha256(self.path.read_bytes()).hexdigest()[:12]
        return f"warp library {self.path} (sha256 {digest}; exports {', '.join(self.exported()) or 'no warp'})"

    def _function(self, name: str, alpha: bool):
        fn = getattr(self._lib, name)
        arguments = [ctypes.POINTER(ctypes.c_float), ctypes.POINTER(ctypes.c_float), ctypes.c_size_t]
        fn.argtypes = arguments + ([ctypes.c_float] if alpha else [])
        fn.restype = None
        return fn

    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        """The library's sampler and pdf for `name`; None if it does not export the sampler, WarpUnavailable if
        it exports the sampler without its pdf."""
        if name not in DIMENSIONS or not hasattr(self._lib, name):
            return None
        if not hasattr(self._lib, name + "_pdf"):
            raise WarpUnavailable(f"{self.path.name} exports {name} but not {name}_pdf: a sampler cannot be "
                                  "checked without its density")
        takes_alpha = name in WITH_ALPHA
        sample_fn, pdf_fn = self._function(name, takes_alpha), self._function(name + "_pdf", takes_alpha)
        extra = (ctypes.c_float(alpha),) if takes_alpha else ()
        dim = DIMENSIONS[name]

        def sample(u: np.ndarray) -> np.ndarray:
            u32 = _float32(u, 2)
            out = np.zeros((len(u32), dim), np.float32)
            sample_fn(_pointer(u32), _pointer(out), len(u32), *extra)
            return out.astype(np.float64)

        def pdf(p: np.ndarray) -> np.ndarray:
            p32 = _float32(p, p.shape[1] if np.ndim(p) == 2 else dim)
            out = np.zeros(len(p32), np.float32)
            pdf_fn(_pointer(p32), _pointer(out), len(p32), *extra)
            return out.astype(np.float64)

        # The library takes float32: a u of 1 - 2^-53 reaches it as 1, which the hard-input check forgives.
        sample.input_dtype = np.float32

        def native_run(n: int):
            u = np.random.default_rng(1).random((n, 2), dtype=np.float32)
            out = np.empty((n, dim), np.float32)
            return lambda: sample_fn(_pointer(u), _pointer(out), n, *extra)

        return WarpFunctions(sample, pdf, native_run)
