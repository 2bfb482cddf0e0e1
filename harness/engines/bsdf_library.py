"""A shared library of BSDFs through the C ABI of include/mcval_bsdfs.h (ours, build/libmcval_bsdfs.so, or a
user's), called on numpy arrays in a process of its own (harness/engines/library_process.py): a crash in one
BSDF's function fails that call, with the signal, and the next call starts the library again."""
from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from harness.engines.base import BsdfFunctions
from harness.engines.library_process import LibraryProcess
from harness.engines.python_child import ChildFailed, ChildRaised, seconds_from_env

#: Seconds one call into the library may take before its process is killed: $MCVAL_BSDF_TIMEOUT, else this.
TIMEOUT_ENV = "MCVAL_BSDF_TIMEOUT"
DEFAULT_TIMEOUT = 120.0
_CHILD = "harness.engines.bsdf_library_child"
#: The functions of one BSDF, as the ABI names them after bsdf_NAME_.
FUNCTIONS = ("params", "eval", "pdf", "sample")


class BsdfUnavailable(RuntimeError):
    """A BSDF the library cannot be checked on, with one line saying why (a function of the four missing)."""


def call_timeout() -> float:
    """$MCVAL_BSDF_TIMEOUT if set (a positive number of seconds), else DEFAULT_TIMEOUT."""
    return seconds_from_env(TIMEOUT_ENV, DEFAULT_TIMEOUT)


def parameter_names(name: str, text: str | None) -> list[str]:
    """The names in bsdf_NAME_params' text (spaces around them ignored); BsdfUnavailable, in one line, for a NULL
    pointer or a name that is empty or no identifier (names separated by spaces, a trailing comma)."""
    if text is None:
        raise BsdfUnavailable(f"bsdf_{name}_params is NULL: give \"\" for a BSDF without parameters")
    names = [n.strip() for n in text.split(",")] if text.strip() else []
    bad = [n for n in names if not n or not n.isidentifier()]
    if bad:
        raise BsdfUnavailable(f"bsdf_{name}_params is {text!r}: expected names (letters, digits, _) separated by "
                              f"commas, e.g. \"alpha,eta\" (not {bad[0]!r})")
    return names


def _rows(a: np.ndarray, columns: int) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(a, np.float32).reshape(-1, columns))


def _incident(wi: np.ndarray) -> np.ndarray:
    """wi as rows, or its one row where every row is the same (the usual call: one wi, many wo): the child
    repeats it, so that half the floats cross the pipe."""
    rows = _rows(wi, 3)
    return rows[:1] if len(rows) > 1 and (rows == rows[0]).all() else rows


class BsdfLibrary:
    """The BSDFs a shared library exports: `names`, each one's `parameters`, and `functions` at given values."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path).resolve()
        if not self.path.is_file():
            raise ValueError(f"BSDF library {path}: no such file")
        self._process = LibraryProcess(self.path, _CHILD, call_timeout)
        #: Why the library could not be loaded (its constructor crashed, hung or exited): every BSDF fails so.
        self.load_failure: ChildFailed | None = None
        try:
            self._found: dict[str, dict] = self._process.call("bsdfs", str(self.path), what="loading it")
        except ChildRaised as e:
            raise ValueError(f"BSDF library {path}: cannot load it as a shared library ({e.original or e})") from None
        except ChildFailed as e:
            self.load_failure, self._found = e, {}

    def __reduce__(self):
        return BsdfLibrary, (self.path,)

    @property
    def names(self) -> list[str]:
        """Every NAME of which the library defines a bsdf_NAME_* symbol, sorted."""
        return sorted(self._found)

    def parameters(self, name: str) -> list[str]:
        """The parameter names bsdf_NAME_params gives; BsdfUnavailable where a function of the four is missing."""
        entry = self._found.get(name)
        if entry is None:
            raise BsdfUnavailable(f"{self.path.name} exports no BSDF {name} (it exports {', '.join(self.names) or 'none'})")
        missing = [f"bsdf_{name}_{f}" for f in FUNCTIONS if f not in entry["functions"]]
        if missing:
            raise BsdfUnavailable(f"{self.path.name} exports {name} without {', '.join(missing)}: a BSDF is checked "
                                  "through all four functions of include/mcval_bsdfs.h")
        try:
            return parameter_names(name, entry["params_text"])
        except BsdfUnavailable as e:
            raise BsdfUnavailable(f"{self.path.name}: {e}") from None

    def version(self) -> str:
        digest = hashlib.sha256(self.path.read_bytes()).hexdigest()[:12]
        exports = (f"not loaded: {self.load_failure.reason}" if self.load_failure else
                   f"exports {', '.join(self.names) or 'no BSDF'}")
        return f"BSDF library {self.path} (sha256 {digest}; {exports})"

    def functions(self, name: str, values: dict[str, float]) -> BsdfFunctions:
        """`name` at parameter `values` (every parameter it names, no other); ValueError naming what is
        missing or unknown, BsdfUnavailable, or ChildFailed when the library could not be loaded."""
        if self.load_failure is not None:
            raise ChildFailed(f"{self.load_failure.reason}: {name} could not be checked", self.load_failure.output)
        names = self.parameters(name)
        unknown, missing = sorted(set(values) - set(names)), [p for p in names if p not in values]
        if unknown or missing:
            raise ValueError(f"{name} takes the parameters {', '.join(names) or '(none)'}: "
                             + "; ".join([*([f"{', '.join(unknown)} unknown"] if unknown else []),
                                          *([f"{', '.join(missing)} not given"] if missing else [])]))
        params = np.array([values[p] for p in names] or [0.0], np.float32)
        at = " ".join([name, *(f"{p}={values[p]:g}" for p in names)])

        def value_or_pdf(kind: str):
            def call(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
                out = self._process.call("eval_or_pdf", name, kind, params, _incident(wi), _rows(wo, 3),
                                         what=f"bsdf_{name}_{kind} ({at})")
                return out.astype(np.float64)
            return call

        def sample(wi: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            out = self._process.call("sample", name, params, _incident(wi), _rows(u, 3),
                                     what=f"bsdf_{name}_sample ({at})")
            return tuple(a.astype(np.float64) for a in out)

        return BsdfFunctions(name, {p: float(values[p]) for p in names}, value_or_pdf("eval"), value_or_pdf("pdf"),
                             sample)
