"""Our roughconductor's Beckmann with visible normals keeps Smith's exact masking, so that its pdf is the density it
samples, at grazing incidence too (every variant's checks, against Mitsuba's: tests/bsdfs/test_reference.py)."""
from pathlib import Path

from harness.bsdfs.checks import draw, incident, sampling_checks
from harness.engines.bsdf_library import BsdfLibrary

LIBRARY = Path(__file__).resolve().parents[2] / "build" / "libmcval_bsdfs.so"


def test_grazing_beckmann_visible_normals_match_their_pdf_at_a_million_samples():
    """Where Mitsuba's rational approximation of the masking term (docs/findings.md) fails these checks."""
    bsdf = BsdfLibrary(LIBRARY).functions("roughconductor", {"alpha": 0.5, "eta": 0.2, "k": 3.0, "ggx": 0,
                                                             "sample_visible": 1})
    sampling, normalisation, _, _ = sampling_checks(bsdf, draw(bsdf, incident(85.0), 1_000_000, 0))
    sampling.decide(0.01)
    assert sampling.verdict == "PASS" and normalisation.verdict == "PASS", (sampling.summary, normalisation.summary)
