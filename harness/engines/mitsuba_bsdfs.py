"""Mitsuba 3's BSDF plugins as BsdfFunctions, for the BSDF checks against the same plugin: a BSDF of the C ABI
(include/mcval_bsdfs.h) whose NAME is a Mitsuba plugin, its parameters given in Mitsuba's names, in a process of
its own (Mitsuba's loader must not end the run: harness/engines/mitsuba_bsdf_child.py)."""
from __future__ import annotations

import numpy as np

from harness.engines.base import BsdfFunctions
from harness.engines.library_process import LibraryProcess
from harness.engines.python_child import seconds_from_env

_CHILD = "harness.engines.mitsuba_bsdf_child"
#: Seconds one call may take (Mitsuba compiles its kernels at the first): $MCVAL_BSDF_TIMEOUT, else this.
DEFAULT_TIMEOUT = 300.0
#: Mitsuba's plugins the checks compare with, by the ABI's NAME, and the parameters each is checked at (the
#: ABI's names, as our library exports them: `ggx` for Mitsuba's `distribution`).
PARAMETERS = {"conductor": ["eta", "k", "specular_reflectance"], "dielectric": ["int_ior", "ext_ior"],
              "diffuse": ["reflectance"], "plastic": ["int_ior", "ext_ior", "diffuse_reflectance", "nonlinear"],
              "roughconductor": ["alpha", "eta", "k", "ggx", "sample_visible"],
              "roughdielectric": ["alpha", "int_ior", "ext_ior", "ggx", "sample_visible"],
              "roughplastic": ["alpha", "int_ior", "ext_ior", "diffuse_reflectance", "nonlinear", "ggx", "sample_visible"]}
PLUGINS = tuple(PARAMETERS)
#: Parameters Mitsuba takes as a spectrum (given here one value for every channel), and as a flag.
_SPECTRA = ("reflectance", "eta", "k", "specular_reflectance", "diffuse_reflectance")
_FLAGS = ("sample_visible", "nonlinear")


def plugin_spec(name: str, values: dict[str, float]) -> dict | None:
    """The mi.load_dict dictionary of Mitsuba's plugin `name` at these parameter values (the ABI's `ggx` flag as
    Mitsuba's `distribution`), or None where Mitsuba has no such plugin here."""
    if name not in PLUGINS:
        return None
    spec: dict = {"type": name}
    for key, value in values.items():
        if key == "ggx":
            spec["distribution"] = "ggx" if value else "beckmann"
        elif key in _SPECTRA:
            spec[key] = {"type": "rgb", "value": float(value)}
        elif key in _FLAGS:
            spec[key] = bool(value)
        else:
            spec[key] = float(value)
    return spec


class MitsubaBsdfs:
    """Mitsuba's BSDF plugins, called in one child process (started at the first call, again after a failure)."""

    def __init__(self) -> None:
        self._process = LibraryProcess(None, _CHILD, lambda: seconds_from_env("MCVAL_BSDF_TIMEOUT", DEFAULT_TIMEOUT),
                                       name="Mitsuba")

    #: As a library of BSDFs to check (`bsdfs --mitsuba`): no file of its own.
    path = None

    @property
    def names(self) -> list[str]:
        return sorted(PLUGINS)

    def parameters(self, name: str) -> list[str]:
        """The parameters `name` is checked at; ValueError where Mitsuba has no such plugin here."""
        if name not in PARAMETERS:
            raise ValueError(f"Mitsuba's plugins checked here are {', '.join(PLUGINS)}, not {name}")
        return list(PARAMETERS[name])

    def version(self) -> str:
        from importlib.metadata import version  # not Mitsuba's import: that runs in the child only

        return f"Mitsuba {version('mitsuba')} plugins, in a process of their own"

    def _call(self, function: str, *args, what: str):
        return self._process.call(function, *args, what=what)

    def functions(self, name: str, values: dict[str, float]) -> BsdfFunctions | None:
        """Mitsuba's plugin `name` at `values`, or None where it has none of that name."""
        spec = plugin_spec(name, values)
        if spec is None:
            return None
        label = " ".join([name, *(f"{k}={v:g}" for k, v in values.items())])

        def value_or_pdf(kind: str):
            def call(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
                return self._call("eval_or_pdf", spec, kind, np.asarray(wi, np.float32), np.asarray(wo, np.float32),
                                  what=f"{kind} of {label}").astype(np.float64)
            return call

        def sample(wi: np.ndarray, u: np.ndarray):
            out = self._call("sample", spec, np.asarray(wi, np.float32), np.asarray(u, np.float32),
                             what=f"sample of {label}")
            return tuple(np.asarray(a, np.float64) for a in out)

        return BsdfFunctions(f"mitsuba {name}", dict(values), value_or_pdf("eval"), value_or_pdf("pdf"), sample)
