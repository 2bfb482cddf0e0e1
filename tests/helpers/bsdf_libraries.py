"""Our BSDF library, the names of every check and the assertion that all pass, for the BSDF tests (fixtures:
tests/bsdfs/conftest.py)."""
from pathlib import Path

from harness.bsdfs.checks import incident
from harness.bsdfs.evaluate import ALL_CHECKS, check_bsdf_at

#: Our BSDFs, built by `make build`.
OURS = Path(__file__).resolve().parents[2] / "build" / "libmcval_bsdfs.so"
#: Every check, as a row with delta samples and a reference holds them.
EVERY_CHECK = ALL_CHECKS


def assert_every_check_passes(bsdf, theta: float, samples: int, seed: int, level: float, reference) -> dict:
    """The checks of `bsdf` at the polar angle `theta` against `reference`, asserted to hold every check a row may
    hold, each a PASS (the summaries shown where not); returned for the caller's own assertions."""
    results = check_bsdf_at(bsdf, incident(theta), samples, seed, level, reference)
    assert {n: r.verdict for n, r in results.items()} == dict.fromkeys(EVERY_CHECK, "PASS"), \
        (bsdf.label, theta, {n: r.summary for n, r in results.items()})
    return results
