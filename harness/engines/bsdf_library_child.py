"""The child side of a BSDF library (harness/engines/bsdf_library.py): the functions of include/mcval_bsdfs.h
found in its dynamic symbol table and called through ctypes on numpy arrays, in a process of its own."""
from __future__ import annotations

import ctypes
import re

import numpy as np

from harness.engines.warp_library_child import pointer, checked, guarded

_lib: ctypes.CDLL | None = None
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
        defined = {s.name: s["st_size"] for s in (table.iter_symbols() if table else ()) if s["st_shndx"] != "SHN_UNDEF"}
    found: dict[str, dict] = {}
    for symbol in defined:
        match = _SYMBOL.fullmatch(symbol)
        if match:
            found.setdefault(match[1], {"functions": []})["functions"].append(match[2])
    for name, entry in found.items():
        if "params" in entry["functions"]:
            entry["params_text"] = _params_text(f"bsdf_{name}_params", defined[f"bsdf_{name}_params"])
    return found


def _params_text(symbol: str, size: int) -> str | None:
    """The string bsdf_NAME_params gives: through the pointer the ABI declares, or, where the symbol is not the
    size of a pointer, from the array a definition without MCVAL_DECLARE_BSDF made of it; None for a NULL
    pointer."""
    if size != ctypes.sizeof(ctypes.c_void_p):
        return (ctypes.c_char * size).in_dll(_lib, symbol).value.decode(errors="replace")
    text = ctypes.c_char_p.in_dll(_lib, symbol).value
    return None if text is None else text.decode(errors="replace")


def _float32(*arrays) -> list[np.ndarray]:
    return [np.ascontiguousarray(a, np.float32) for a in arrays]


def _function(name: str, kind: str, arguments: int):
    fn = getattr(_lib, f"bsdf_{name}_{kind}")
    fn.argtypes = [_F32] * arguments + [ctypes.c_size_t]
    fn.restype = None
    return fn


def _repeated(wi: np.ndarray, n: int) -> np.ndarray:
    """wi as n rows: one row sent for all of them is repeated here."""
    return np.repeat(wi, n, axis=0) if len(wi) == 1 and n != 1 else wi


def eval_or_pdf(name: str, kind: str, params: np.ndarray, wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """bsdf_NAME_eval or bsdf_NAME_pdf (`kind`) at n rows of wi, wo (n, 3; wi may be one row for all): (n,)
    float32."""
    n = len(wo)
    wi = _repeated(wi, n)
    out = guarded(n, 1)
    _function(name, kind, 4)(*map(pointer, (*_float32(params, wi, wo), out)), n)
    return checked(out, n, 1, {"eval": "value", "pdf": "pdf"}[kind], "rows")[:, 0]


def sample(name: str, params: np.ndarray, wi: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, ...]:
    """bsdf_NAME_sample at n rows of wi (n, 3; or one row for all) and u (n, 3): wo (n, 3), weight (n,), pdf (n,),
    float32."""
    n = len(u)
    wi = _repeated(wi, n)
    wo, weight, pdf = guarded(n, 3), guarded(n, 1), guarded(n, 1)
    _function(name, "sample", 6)(*map(pointer, (*_float32(params, wi, u), wo, weight, pdf)), n)
    return (checked(wo, n, 3, "wo", "rows"), checked(weight, n, 1, "weight", "rows")[:, 0],
            checked(pdf, n, 1, "pdf", "rows")[:, 0])
