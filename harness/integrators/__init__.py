"""One entry per integrator (normals.py, simple.py, ao.py) and the registry that finds and matches them."""
from harness.integrators.entry import AnalyticForm, IntegratorEntry, MitsubaMapping
from harness.integrators.registry import Matched, entries, entry, match, renderer_integrators

__all__ = ["AnalyticForm", "IntegratorEntry", "Matched", "MitsubaMapping", "entries", "entry", "match",
           "renderer_integrators"]
