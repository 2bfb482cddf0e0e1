"""path_no_cosine, an integrator of the test-only renderer build: path with no cosine at the surface
(tests/cpp/path_twins_integrator.cpp, a planted wrong twin). It claims path's image, so its entry is path's and
engines render path in its place."""
import dataclasses

from harness.integrators.path import ENTRY as PATH

ENTRY = dataclasses.replace(PATH, name="path_no_cosine", same_image_as="path")
