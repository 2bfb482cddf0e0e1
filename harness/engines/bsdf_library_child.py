"""The child side of a BSDF library (harness/engines/bsdf_library.py): the functions of include/mcval_bsdfs.h
found in its dynamic symbol table and called through ctypes on numpy arrays, in a process of its own."""
from __future__ import annotations

import ctypes
import re

import numpy as np

from harness.engines.warp_library_child import GUARD, OutputOverrun

_lib: ctypes.CDLL | None = None
_GUARD_BITS = np.uint32(0x7FC0DEAD)
_SYMBOL = re.compile(r"bsdf_(\w+)_(params|eval|pdf|sample)")
_F32 = ctypes.POINTER(ctypes.c_float)


def load(path: str) -> None:
    """Load the library: its constructors run here."""
    global _lib
    _lib = ctypes.CDLL(path)


def bsdfs(path: str) -> dict[str, dict]:
    """Each NAME of which the library defines a bsdf_NAME_* symbol: which of params, eval, pdf and sample it
    defines, and its parameter names (bsdf_NAME_params split at commas) where it defines that."""
    from elftools.elf.elffile import ELFFile

    with open(path, "rb") as f:
        table = ELFFile(f).get_section_by_name(".dynsym")
        defined = [s.name for s in (table.iter_symbols() if table else ()) if s["st_shndx"] != "SHN_UNDEF"]
    found: dict[str, dict] = {}
    for symbol in defined:
        match = _SYMBOL.fullmatch(symbol)
        if match:
            found.setdefault(match[1], {"functions": []})["functions"].append(match[2])
    for name, entry in found.items():
        if "params" in entry["functions"]:
            text = ctypes.c_char_p.in_dll(_lib, f"bsdf_{name}_params").value
            entry["params"] = [] if not text else [p.strip() for p in text.decode(errors="replace").split(",")]
    return found


def _guarded(n: int, columns: int) -> np.ndarray:
    out = np.zeros(n * columns + GUARD, np.float32)
    out.view(np.uint32)[n * columns:] = _GUARD_BITS
    return out


def _checked(out: np.ndarray, n: int, columns: int, what: str) -> np.ndarray:
    if np.any(out.view(np.uint32)[n * columns:] != _GUARD_BITS):
        raise OutputOverrun(f"wrote past the end of its {what} ({n} rows, {columns} float{'s' * (columns > 1)} each)")
    return out[:n * columns].reshape(n, columns)


def _floats(a) -> tuple[np.ndarray, object]:
    a = np.ascontiguousarray(a, np.float32)
    return a, a.ctypes.data_as(_F32)


def _function(name: str, kind: str, arguments: int):
    fn = getattr(_lib, f"bsdf_{name}_{kind}")
    fn.argtypes = [_F32] * arguments + [ctypes.c_size_t]
    fn.restype = None
    return fn


def eval_or_pdf(name: str, kind: str, params: np.ndarray, wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """bsdf_NAME_eval or bsdf_NAME_pdf (`kind`) at n rows of wi, wo (n, 3): (n,) float32."""
    n = len(wi)
    (p, pp), (i, ip), (o, op) = _floats(params), _floats(wi), _floats(wo)
    out = _guarded(n, 1)
    _function(name, kind, 4)(pp, ip, op, out.ctypes.data_as(_F32), n)
    return _checked(out, n, 1, {"eval": "value", "pdf": "pdf"}[kind])[:, 0]


def sample(name: str, params: np.ndarray, wi: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, ...]:
    """bsdf_NAME_sample at n rows of wi (n, 3) and u (n, 3): wo (n, 3), weight (n,), pdf (n,), float32."""
    n = len(wi)
    (p, pp), (i, ip), (v, up) = _floats(params), _floats(wi), _floats(u)
    wo, weight, pdf = _guarded(n, 3), _guarded(n, 1), _guarded(n, 1)
    _function(name, "sample", 6)(pp, ip, up, *(a.ctypes.data_as(_F32) for a in (wo, weight, pdf)), n)
    return (_checked(wo, n, 3, "wo"), _checked(weight, n, 1, "weight")[:, 0], _checked(pdf, n, 1, "pdf")[:, 0])
