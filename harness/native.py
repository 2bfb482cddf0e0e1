"""The renderer's compiled Python module `mcval_renderer` (built by CMake into build/python, see the
Makefile): the one place that imports it, so a missing build is one clear error."""
from __future__ import annotations

from types import ModuleType


def renderer_module() -> ModuleType:
    """The imported `mcval_renderer`; RuntimeError naming the command that builds it if it is missing."""
    try:
        import mcval_renderer
    except ImportError as e:
        raise RuntimeError("the renderer's Python module `mcval_renderer` is not built or not on the path: "
                           "run `make build` (it builds it into build/python)") from e
    return mcval_renderer
