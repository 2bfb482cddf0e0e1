"""Warps as users have them, turned into the numpy functions the checks call.

* numpy functions: (N, 2) float64 uniforms -> (N, 2) or (N, 3) points, and
  points -> (N,) densities. float32 results are widened to float64; a pdf that
  returns a scalar or a single value (a constant density) is broadcast to N.
* Mitsuba / Dr.Jit functions passed as they are (e.g. mi.warp.square_to_beckmann):
  recognised by their nanobind function type or their module, or by a TypeError
  on numpy input. They are called on mi.Point2f uniforms and mi.Point2f /
  mi.Vector3f points (float32, so a u of 1 - 2^-53 reaches them as 1) of the
  Mitsuba variant in force, which must be a vectorised one (llvm_*, cuda_*);
  their results come back as float64 numpy arrays.
* Extra positional arguments (e.g. Beckmann's alpha) are passed on after the array.

Wrong shapes raise a ValueError naming the function, the shape it returned and
the shape expected. `masked_to_domain` zeroes a pdf outside its domain, as
Mitsuba's `*_pdf` functions expect their caller to (they do not test the domain).
"""
from __future__ import annotations

import sys
from typing import Any, Callable

import numpy as np

from harness.warps.domains import Domain, get_domain


def is_drjit_function(fn: Any) -> bool:
    """Whether fn is a Mitsuba or Dr.Jit function (a nanobind function, or one defined in those packages)."""
    module = getattr(fn, "__module__", None) or ""
    return type(fn).__module__ == "nanobind" or module.split(".")[0] in ("mitsuba", "drjit")


def function_name(fn: Any) -> str:
    """A name for error messages: the qualified name of fn, else its repr."""
    return getattr(fn, "__qualname__", None) or getattr(fn, "__name__", None) or repr(fn)


def _mitsuba(fn: Any):
    mi = sys.modules.get("mitsuba")
    if mi is None:
        raise TypeError(f"{function_name(fn)} looks like a Dr.Jit function, but mitsuba is not imported: "
                        "import mitsuba and set a vectorised variant (e.g. mi.set_variant('llvm_ad_rgb'))")
    variant = mi.variant()
    if not variant or variant.startswith("scalar"):
        raise ValueError(f"{function_name(fn)} is a Dr.Jit function: it needs a vectorised Mitsuba variant "
                         f"(llvm_*, cuda_*) to take arrays, and the variant in force is {variant}")
    return mi


class _Call:
    """fn called on a numpy array (then on Dr.Jit arrays, once it is known to need them), plus extra args."""

    def __init__(self, fn: Callable, args: tuple = (), input_dtype: Any = None) -> None:
        if not callable(fn):
            raise TypeError(f"expected a function, got {type(fn).__name__}")
        self.fn, self.args = fn, tuple(args)
        self.drjit = is_drjit_function(fn)
        self._input_dtype = None if input_dtype is None else np.dtype(input_dtype).type

    @property
    def input_dtype(self) -> type:
        """The precision the function receives its input in (hard_inputs judges u = 1 in it): as given, else
        float32 for a Dr.Jit function and float64 for numpy."""
        if self._input_dtype is not None:
            return self._input_dtype
        return np.float32 if self.drjit else np.float64

    def _drjit_call(self, x: np.ndarray, extra: tuple) -> np.ndarray:
        mi = _mitsuba(self.fn)
        if not len(x):  # Dr.Jit refuses arrays of size 0 (operands of incompatible sizes): one point, then none
            return self._drjit_call(np.full((1, np.shape(x)[1]), 0.5), extra)[:0]
        a = np.ascontiguousarray(np.asarray(x, dtype=np.float32).T)
        arg = mi.Point2f(a) if a.shape[0] == 2 else mi.Vector3f(a)
        out = np.array(self.fn(arg, *self.args, *extra), dtype=np.float64)
        return out.T if out.ndim == 2 else out

    def raw(self, x: np.ndarray, extra: tuple = ()) -> Any:
        if self._input_dtype is not None and not self.drjit:
            x = np.asarray(x, dtype=self._input_dtype)
        if self.drjit:
            return self._drjit_call(x, extra)
        try:
            return self.fn(x, *self.args, *extra)
        except TypeError as numpy_error:
            if "mitsuba" not in sys.modules:
                raise
            try:
                out = self._drjit_call(x, extra)
            except Exception:
                raise numpy_error from None
            self.drjit = True
            return out


class NumpySampler(_Call):
    """A sampler over numpy arrays: (N, 2) uniforms in [0,1)^2 -> (N, 2) or (N, 3) float64 points."""

    def __call__(self, u: np.ndarray) -> np.ndarray:
        n = len(u)
        out = np.asarray(self.raw(u), dtype=np.float64)
        if out.ndim != 2 or out.shape[0] != n or out.shape[1] not in (2, 3):
            raise ValueError(f"sample function {function_name(self.fn)} returned shape {out.shape} for {n} "
                             f"uniforms of shape {np.shape(u)}; expected ({n}, 2) or ({n}, 3)")
        return out


class NumpyPdf(_Call):
    """A pdf over numpy arrays: (N, 2) or (N, 3) points -> (N,) float64 densities (a constant broadcast)."""

    def __call__(self, points: np.ndarray, *extra: Any) -> np.ndarray:
        n = len(points)
        out = np.asarray(self.raw(points, extra), dtype=np.float64)
        if out.size == 1:
            return np.full(n, float(out.reshape(-1)[0]))
        if out.shape != (n,):
            raise ValueError(f"pdf function {function_name(self.fn)} returned shape {out.shape} for {n} points "
                             f"of shape {np.shape(points)}; expected ({n},), or one value for a constant density")
        return out


def masked_to_domain(pdf: Callable, domain: str | Domain) -> Callable[..., np.ndarray]:
    """pdf where `domain` contains the point (Domain.contains, with its float32 slack), 0 elsewhere.

    For densities that leave the domain test to their caller, as Mitsuba documents for its
    `mi.warp.*_pdf` (the cosine hemisphere's is negative below the horizon, the uniform sphere's is
    one constant everywhere). pdf may be a numpy or a Dr.Jit function; extra arguments given to the
    result (e.g. check_warp's `args`) are passed on to it.
    """
    dom = get_domain(domain) if isinstance(domain, str) else domain
    inner = NumpyPdf(pdf)

    def masked(points: np.ndarray, *args: Any) -> np.ndarray:
        points = np.asarray(points, dtype=np.float64)
        values = inner(points, *args)
        return np.where(dom.inside(points), values, 0.0)

    masked.__name__ = masked.__qualname__ = f"{function_name(pdf)}, masked to the {dom.name}"
    return masked
