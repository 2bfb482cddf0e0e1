"""One entry per integrator (normals.py, simple.py, ao.py) and the registry that finds and matches them."""
from harness.integrators.entry import AnalyticForm, IntegratorEntry
from harness.integrators.registry import Matched, entries, entry, match

__all__ = ["AnalyticForm", "IntegratorEntry", "Matched", "entries", "entry", "match"]
