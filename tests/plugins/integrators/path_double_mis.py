"""path_double_mis, an integrator of the test-only renderer build: path with MIS that counts the light a BSDF sample
finds at full weight beside the emitter sample (tests/cpp/path_twins_integrator.cpp, a planted wrong twin). It
claims path's image, so its entry is path's and engines render path in its place."""
import dataclasses

from harness.integrators.path import ENTRY as PATH

ENTRY = dataclasses.replace(PATH, name="path_double_mis", same_image_as="path")
