"""ao_uniform, an integrator of the test-only renderer build: ao's image drawn with directions uniform on the
hemisphere and weighted by 2 cos (tests/cpp/ao_uniform_integrator.cpp). The same mean as ao, so its entry is
ao's, except that Mitsuba's mapping (cosine-weighted BSDF sampling) is not its estimator."""
import dataclasses

from harness.integrators.ao import ENTRY as AO

ENTRY = dataclasses.replace(AO, name="ao_uniform", same_estimator_in_mitsuba=False, estimator_differs=None)
