"""The integrators a build registers, read from the sources that register them (MCVAL_REGISTER_INTEGRATOR), so
that a test pins the registry to the files and a new integrator file needs no edit of the tests."""
from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_REGISTERED = re.compile(r'MCVAL_REGISTER_INTEGRATOR\(\{\s*"([A-Za-z0-9_]+)"')


def _names(files) -> list[str]:
    return sorted(name for path in files for name in _REGISTERED.findall(path.read_text()))


#: The product's integrators, sorted (renderer/integrators/*.cpp).
PRODUCT = _names(sorted((ROOT / "renderer" / "integrators").glob("*.cpp")))
#: The test build's: the product's and those of tests/cpp/*_integrator.cpp, which CMake links into it
#: (render_with_test_integrators).
TEST_BUILD = sorted(PRODUCT + _names(sorted((ROOT / "tests" / "cpp").glob("*_integrator.cpp"))))


def name_list(names: list[str]) -> str:
    """"a, b or c", as the renderer lists its choices."""
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
