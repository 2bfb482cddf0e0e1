"""direct_area_pdf, an integrator of the test-only renderer build: direct with the area light's density left in area measure
(tests/cpp/direct_twins_integrator.cpp, a planted wrong twin). It claims direct's image, so its entry is direct's
and engines render direct in its place; tests/images/test_direct_twins.py runs it where the harness asks for
direct."""
import dataclasses

from harness.integrators.direct import ENTRY as DIRECT

ENTRY = dataclasses.replace(DIRECT, name="direct_area_pdf", same_image_as="direct")
