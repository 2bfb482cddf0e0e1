"""Our BSDF library and the names of every check, for the BSDF tests (fixtures: tests/bsdfs/conftest.py)."""
from pathlib import Path

from harness.bsdfs.evaluate import ALL_CHECKS

#: Our BSDFs, built by `make build`.
OURS = Path(__file__).resolve().parents[2] / "build" / "libmcval_bsdfs.so"
#: Every check, as a row with delta samples and a reference holds them.
EVERY_CHECK = ALL_CHECKS
