"""Warp conformance: samplers checked against their pdfs and against a reference.

`check_warp` is the entry point for a warp of your own; `masked_to_domain` adapts a sampler that
returns a validity mask (as Mitsuba's do)."""
from harness.warps.adapters import masked_to_domain
from harness.warps.evaluate import check_warp

__all__ = ["check_warp", "masked_to_domain"]
