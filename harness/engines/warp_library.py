"""A C or C++ warp library as an engine of warps alone: the functions of include/mcval_warps.h, float32 and
interleaved, called on numpy arrays (docs/engines.md#warps-in-c-or-c).

The library runs in a child process of its own (harness/engines/library_process.py): a segfault, an abort(), a
write past its output, an exit() or a hang costs the warp whose call it was (a crash while loading: every
warp of the library), with the library, the function and the signal or exit status in one line. Each call
has a time limit ($MCVAL_WARP_TIMEOUT seconds); a child that failed is replaced at the next call."""
from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from harness.engines.base import Engine, WarpFunctions
from harness.engines.library_process import LibraryProcess
from harness.engines.python_child import ChildFailed, ChildRaised, seconds_from_env

#: Each warp of the ABI and the dimension of its points.
DIMENSIONS = {"square_to_uniform_square": 2, "square_to_tent": 2, "square_to_uniform_disk": 2,
              "square_to_uniform_sphere": 3, "square_to_uniform_hemisphere": 3, "square_to_cosine_hemisphere": 3,
              "square_to_beckmann": 3}
#: The warps that take a parameter (last, as a float).
WITH_ALPHA = ("square_to_beckmann",)
#: Seconds one call into the library may take (a million samples, or one timed throughput run) before its
#: process is killed: $MCVAL_WARP_TIMEOUT, else this.
TIMEOUT_ENV = "MCVAL_WARP_TIMEOUT"
DEFAULT_TIMEOUT = 120.0
_CHILD = "harness.engines.warp_library_child"


class WarpUnavailable(RuntimeError):
    """A warp the library cannot be checked on, with one line saying why (a sampler without its pdf)."""


def call_timeout() -> float:
    """$MCVAL_WARP_TIMEOUT if set (a positive number of seconds), else DEFAULT_TIMEOUT."""
    return seconds_from_env(TIMEOUT_ENV, DEFAULT_TIMEOUT)


def _float32(a: np.ndarray, columns: int) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(a, np.float32).reshape(-1, columns))


class WarpLibraryEngine(Engine):
    """The warps a shared library exports. Its throughput is reported, not judged: the floor is for mcval's."""

    throughput_judged = False
    #: A warp the library does not export is left out of the matrix, not failed.
    warps_optional = True

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path).resolve()
        if not self.path.is_file():
            raise ValueError(f"--warp-library {path}: no such file")
        self.name = self.label = self.path.stem.removeprefix("lib")
        self._process = LibraryProcess(self.path, _CHILD, call_timeout)
        #: Why the library could not be loaded (its constructor crashed, hung or exited): every warp fails so.
        self.load_failure: ChildFailed | None = None
        try:
            names = [name + pdf for name in DIMENSIONS for pdf in ("", "_pdf")]
            self._exports = set(self._call("exports", names, what="loading it"))
        except ChildRaised as e:
            raise ValueError(f"--warp-library {path}: cannot load it as a shared library ({e.original or e})"
                             ) from None
        except ChildFailed as e:
            self.load_failure, self._exports = e, set()

    def __reduce__(self):
        return WarpLibraryEngine, (self.path,)

    def _call(self, function: str, *args, what: str):
        """`function` of warp_library_child in the library's process (harness/engines/library_process.py)."""
        return self._process.call(function, *args, what=what)

    def exported(self) -> list[str]:
        """The warps of the ABI whose sampler the library exports."""
        return [name for name in DIMENSIONS if name in self._exports]

    def version(self) -> str:
        digest = hashlib.sha256(self.path.read_bytes()).hexdigest()[:12]
        exports = (f"not loaded: {self.load_failure.reason}" if self.load_failure else
                   f"exports {', '.join(self.exported()) or 'no warp'}")
        return f"warp library {self.path} (sha256 {digest}; {exports})"

    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        """The library's sampler and pdf for `name`; None if it does not export the sampler, WarpUnavailable if
        it exports the sampler without its pdf, ChildFailed if the library could not be loaded."""
        if self.load_failure is not None and name in DIMENSIONS:
            raise ChildFailed(f"{self.load_failure.reason}: {name} could not be checked", self.load_failure.output)
        if name not in DIMENSIONS or name not in self._exports:
            return None
        if name + "_pdf" not in self._exports:
            raise WarpUnavailable(f"{self.path.name} exports {name} but not {name}_pdf: a sampler cannot be "
                                  "checked without its density")
        a = float(alpha) if name in WITH_ALPHA else None
        dim = DIMENSIONS[name]
        at = "" if a is None else f" (alpha={a:g})"

        def sample(u: np.ndarray) -> np.ndarray:
            out = self._call("call", name, a, _float32(u, 2), dim, what=name + at)
            return out.astype(np.float64)

        def pdf(p: np.ndarray) -> np.ndarray:
            p32 = _float32(p, p.shape[1] if np.ndim(p) == 2 else dim)
            return self._call("call", name + "_pdf", a, p32, 1, what=f"{name}_pdf{at}").reshape(-1).astype(np.float64)

        # The library takes float32: a u of 1 - 2^-53 reaches it as 1, which the hard-input check forgives.
        sample.input_dtype = np.float32

        def native_run(n: int):
            # The samples stay in the library's process: a timed call sends only its key there and back.
            key = (name, a, n)
            self._call("prepare", key, name, a, n, dim, what=name + at)
            return lambda: self._call("run", key, what=name + at)

        return WarpFunctions(sample, pdf, native_run)
