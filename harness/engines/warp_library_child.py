"""The child side of a --warp-library (harness/engines/warp_library.py): the library loaded with ctypes and its
functions called on numpy arrays, in a process of its own (harness/engines/python_child.py)."""
from __future__ import annotations

import ctypes

import numpy as np

#: Floats after each output buffer, filled with a NaN no warp computes: a library that writes past its n
#: results changes them, and its call fails instead of passing on what it wrote over.
GUARD = 1024
_GUARD_BITS = np.uint32(0x7FC0DEAD)
_lib: ctypes.CDLL | None = None
_runs: dict[tuple, tuple] = {}


class OutputOverrun(RuntimeError):
    """The function wrote past the end of the output buffer it was given."""


def load(path: str) -> None:
    """Load the library: its constructors run here."""
    global _lib
    _lib = ctypes.CDLL(path)


def exports(names: list[str]) -> list[str]:
    """Those of `names` the library exports."""
    return [name for name in names if hasattr(_lib, name)]


def _function(name: str, alpha: float | None):
    fn = getattr(_lib, name)
    fn.argtypes = [ctypes.POINTER(ctypes.c_float), ctypes.POINTER(ctypes.c_float), ctypes.c_size_t] + (
        [] if alpha is None else [ctypes.c_float])
    fn.restype = None
    return fn, (() if alpha is None else (ctypes.c_float(alpha),))


def pointer(a: np.ndarray):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_float))


def guarded(n: int, columns: int) -> np.ndarray:
    """An output buffer of n rows of `columns` floats, with GUARD floats of the guard value after them."""
    out = np.zeros(n * columns + GUARD, np.float32)
    out.view(np.uint32)[n * columns:] = _GUARD_BITS
    return out


def checked(out: np.ndarray, n: int, columns: int, what: str = "output", rows: str = "points") -> np.ndarray:
    """The (n, columns) rows of a `guarded` buffer; OutputOverrun if the function wrote over its guard."""
    if np.any(out.view(np.uint32)[n * columns:] != _GUARD_BITS):
        raise OutputOverrun(f"wrote past the end of its {what} ({n} {rows}, {columns} float{'s' * (columns > 1)} each)")
    return out[:n * columns].reshape(n, columns)


def call(name: str, alpha: float | None, inputs: np.ndarray, columns: int) -> np.ndarray:
    """`name`(inputs, out, n[, alpha]) on n rows of float32 `inputs`: the (n, columns) float32 it wrote."""
    fn, extra = _function(name, alpha)
    inputs = np.ascontiguousarray(inputs, np.float32)
    n = len(inputs)
    out = guarded(n, columns)
    fn(pointer(inputs), pointer(out), n, *extra)
    return checked(out, n, columns)


def prepare(key: tuple, name: str, alpha: float | None, n: int, columns: int) -> None:
    """Uniforms and an output buffer for `run(key)`: n samples of the throughput check, warped in place."""
    u = np.random.default_rng(1).random((n, 2), dtype=np.float32)
    _runs[key] = (*_function(name, alpha), u, np.empty(n * columns + GUARD, np.float32), n)


def run(key: tuple) -> None:
    fn, extra, u, out, n = _runs[key]
    fn(pointer(u), pointer(out), n, *extra)
