"""Mitsuba 3's own warps, passed to check_warp as they are and by their names (so also judged against the closed
forms of those names): the harness must accept them, and find the one real bug among them (Beckmann's NaN
direction at u = (0.5, 0.5))."""
import numpy as np
import pytest

from harness.engines.mitsuba import load_mitsuba
from harness.warps.adapters import masked_to_domain
from harness.warps.evaluate import check_warp

#: Fewer samples than the matrix: the file runs in seconds.
SAMPLES = 200_000
SEEDS = (0, 1, 2)

#: (mi.warp sampler, domain, extra arguments). Mitsuba has no uniform-square warp with a pdf; the cone
#: fits a domain at cos_cutoff 0 (the hemisphere) and -1 (the sphere).
CORRECT = [
    ("square_to_tent", "tent", ()),
    ("square_to_uniform_disk", "disk", ()),
    ("square_to_uniform_disk_concentric", "disk", ()),
    ("square_to_uniform_sphere", "sphere", ()),
    ("square_to_uniform_hemisphere", "hemisphere", ()),
    ("square_to_cosine_hemisphere", "hemisphere", ()),
    ("square_to_uniform_cone", "hemisphere", (0.0,)),
    ("square_to_uniform_cone", "sphere", (-1.0,)),
]
BECKMANN_ALPHAS = (0.05, 0.3, 1.0)


@pytest.fixture
def mi():
    """Mitsuba with the llvm variant in force (another test may have switched to scalar_rgb)."""
    return load_mitsuba()


def _functions(mi, name: str, domain: str):
    sample, pdf = getattr(mi.warp, name, None), getattr(mi.warp, name + "_pdf", None)
    assert sample is not None and pdf is not None, f"Mitsuba {mi.__version__} has no {name} with a pdf"
    # Mitsuba's pdfs leave the domain test to their caller (the cosine pdf is negative below the horizon).
    return sample, masked_to_domain(pdf, domain)


def _failures(result) -> dict:
    return {k: c.summary for k, c in result.checks.items() if c.passed is False}


@pytest.mark.slow
@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("name, domain, args", CORRECT, ids=[f"{n.removeprefix('square_to_')}-{d}"
                                                             for n, d, _ in CORRECT])
def test_mitsuba_warp_passes(mi, name, domain, args, seed):
    sample, pdf = _functions(mi, name, domain)
    result = check_warp(sample, pdf, domain, seed=seed, args=args, samples=SAMPLES, name=name)
    assert result.passed, _failures(result)
    for check in result.checks.values():
        assert all(f.kind.key == "zero_pdf_boundary" for f in check.warnings), check.summary


@pytest.mark.parametrize("name, domain", [("square_to_tent", "tent"), ("square_to_cosine_hemisphere", "hemisphere")])
def test_mitsuba_boundary_samples_are_warnings(mi, name, domain):
    # The tent's corner at u = 0 and the cosine hemisphere's horizon at u = (0, 0) have pdf 0: 0/0, not a bug.
    sample, pdf = _functions(mi, name, domain)
    result = check_warp(sample, pdf, domain, samples=SAMPLES, name=name)
    hard = result.checks["hard_inputs"]
    assert result.verdict == "WARN" and hard.verdict == "WARN"
    assert [f.kind.key for f in hard.findings] == ["zero_pdf_boundary"]
    assert hard.findings[0].examples[0].startswith("u=(0.0, 0.0)")
    assert "0/0: guard it" in hard.findings[0].text()


@pytest.mark.slow
@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("alpha", BECKMANN_ALPHAS)
def test_mitsuba_beckmann_nan_at_the_centre_is_found_first(mi, alpha, seed):
    # Mitsuba 3.9's square_to_beckmann returns (nan, nan, 1) at u = (0.5, 0.5), for every alpha.
    sample, pdf = _functions(mi, "square_to_beckmann", "hemisphere")
    result = check_warp(sample, pdf, "hemisphere", seed=seed, args=(alpha,), samples=SAMPLES,
                        params={"alpha": alpha}, name="square_to_beckmann")
    assert _failures(result).keys() == {"hard_inputs"}
    hard = result.checks["hard_inputs"]
    first = hard.findings[0]
    assert first.severity == "FAIL" and first.kind.key == "nan_sample" and first.count == 1
    assert first.examples[0].startswith("u=(0.5, 0.5) → sample (nan, nan, 1)")
    assert hard.summary.startswith("NaN/Inf sample ×1: u=(0.5, 0.5)")
    assert hard.figure == 1


def test_drjit_functions_pass_unchanged_with_a_parameter(mi):
    # Both functions straight from mi.warp, cos_cutoff passed on to both (the sphere has no outside to mask).
    result = check_warp(mi.warp.square_to_uniform_cone, mi.warp.square_to_uniform_cone_pdf, "sphere",
                        args=(-1.0,), samples=SAMPLES)
    assert result.passed, _failures(result)
    assert result.params == [-1.0]


def test_unmasked_mitsuba_pdf_fails_only_off_the_domain(mi):
    # As Mitsuba documents, its cosine pdf does not test the domain: below the horizon it is negative.
    result = check_warp(mi.warp.square_to_cosine_hemisphere, mi.warp.square_to_cosine_hemisphere_pdf,
                        "hemisphere", samples=SAMPLES)
    assert _failures(result).keys() == {"domain"}
    domain = result.checks["domain"]
    assert domain.findings[0].kind.key == "pdf_off_domain"
    assert domain.details["pdf_nonzero_outside"] > 0


def test_masked_to_domain_zeroes_the_pdf_outside(mi):
    pdf = masked_to_domain(mi.warp.square_to_cosine_hemisphere_pdf, "hemisphere")
    v = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [0.6, 0.0, 0.8], [np.nan, 0.0, 1.0]])
    assert pdf(v) == pytest.approx([1 / np.pi, 0.0, 0.8 / np.pi, 0.0], rel=1e-6)
    assert "masked to the hemisphere" in pdf.__name__


def test_drjit_function_in_a_scalar_variant_is_a_clear_error(mi):
    sample = mi.warp.square_to_tent
    mi.set_variant("scalar_rgb")
    try:
        with pytest.raises(ValueError, match="square_to_tent .*vectorised Mitsuba variant.*scalar_rgb"):
            check_warp(sample, lambda p: np.full(len(p), 0.25), "tent", samples=1000)
    finally:
        load_mitsuba()
