"""path_rr_undivided, an integrator of the test-only renderer build: path with Russian roulette that does not divide
by the survival probability (tests/cpp/path_twins_integrator.cpp, a planted wrong twin). It claims path's image,
so its entry is path's and engines render path in its place."""
import dataclasses

from harness.integrators.path import ENTRY as PATH

ENTRY = dataclasses.replace(PATH, name="path_rr_undivided", same_image_as="path")
