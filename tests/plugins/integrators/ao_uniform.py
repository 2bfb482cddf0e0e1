"""ao_uniform, an integrator of the test-only renderer build: ao's image drawn with directions uniform on the
hemisphere and weighted by 2 cos (tests/cpp/ao_uniform_integrator.cpp). The same mean as ao, so its entry is
ao's, and engines render ao in its place, whose estimator (cosine-weighted) is not its own."""
import dataclasses

from harness.integrators.ao import ENTRY as AO

ENTRY = dataclasses.replace(AO, name="ao_uniform", same_image_as="ao")
