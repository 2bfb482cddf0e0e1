"""direct_double_mis, an integrator of the test-only renderer build: direct with MIS weights that double count
(tests/cpp/direct_twins_integrator.cpp, a planted wrong twin). It claims direct's image, so its entry is direct's
and engines render direct in its place; tests/images/test_direct_twins.py runs it where the harness asks for
direct."""
import dataclasses

from harness.integrators.direct import ENTRY as DIRECT

ENTRY = dataclasses.replace(DIRECT, name="direct_double_mis", same_image_as="direct")
