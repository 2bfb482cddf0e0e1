"""path_depth_plus_one, an integrator of the test-only renderer build: path with max_depth off by one
(tests/cpp/path_twins_integrator.cpp, a planted wrong twin). It claims path's image, so its entry is path's and
engines render path in its place."""
import dataclasses

from harness.integrators.path import ENTRY as PATH

ENTRY = dataclasses.replace(PATH, name="path_depth_plus_one", same_image_as="path")
