"""The closed forms the matrix's names promise: each a density of its domain whose exact cells agree with its
cubature, equal to our renderer's pdf and to Mitsuba's; names resolved as users write them."""
import numpy as np
import pytest

from harness.statistics.constants import FLOAT32_QUANTUM
from harness.warps import checks as wc
from harness.warps.adapters import masked_to_domain
from harness.warps.domains import get_domain
from harness.warps.pdf_agreement import pdf_agreement_check
from harness.warps.suite import SUITE
from harness.warps.targets import KNOWN, target_for

KEYS = [s.key for s in SUITE]


@pytest.mark.parametrize("key", KEYS)
def test_each_target_is_a_density_whose_exact_cells_agree_with_its_cubature(key):
    target = target_for(key)
    for quantum in (0.0, FLOAT32_QUANTUM):
        bins, p = target.cells(10**6, quantum)
        assert p.sum() == pytest.approx(1.0, abs=1e-12) and p.max() / p.min() == pytest.approx(1.0, abs=1e-8)
        cubature = wc.expected_probabilities(get_domain(target.domain), target.pdf, bins).values
        assert np.allclose(cubature, p, rtol=1e-7, atol=0)
    # float32 samples limit Beckmann's cells as they limit its pdf's (docs/warps.md#cells)
    assert target_for("beckmann:0.01").cells(10**6, FLOAT32_QUANTUM)[0].shape == (2, 51)
    assert target_for("beckmann:0.05").cells(10**6, FLOAT32_QUANTUM)[0].shape == (45, 51)


def test_every_target_is_0_outside_its_domain():
    rng = np.random.default_rng(0)
    for key in KEYS:
        target = target_for(key)
        outside = get_domain(target.domain).outside
        if outside is not None:
            assert not np.any(target.pdf(outside(rng, 1000)))
    assert not np.any(target_for("uniform_sphere").pdf(np.array([[0.0, 0.0, 0.5], [np.nan, 0.0, 1.0]])))


def _agreement(sample, pdf, target):
    points = sample(np.random.default_rng(1).random((20_000, 2)))
    return pdf_agreement_check(points, pdf, target.pdf, target.label)


@pytest.mark.parametrize("spec", SUITE, ids=KEYS)
def test_each_target_is_our_renderers_pdf(mcval, spec):
    f = mcval.warp(spec.name, spec.alpha)
    check = _agreement(f.sample, f.pdf, target_for(spec.name, spec.alpha))
    assert check.passed, check.summary


@pytest.mark.parametrize("spec", [s for s in SUITE if s.name != "square_to_uniform_square"],
                         ids=[k for k in KEYS if k != "uniform_square"])
def test_each_target_is_mitsubas_pdf(mitsuba, spec):
    # Mitsuba's float32 Beckmann cancels in 1 - cos^2 near the pole: the closed form's sensitivity to one float32
    # ulp of the point is the slack the check allows it, as pdf_vs_mitsuba allows mcval.
    f = mitsuba.warp(spec.name, spec.alpha)
    check = _agreement(f.sample, masked_to_domain(f.pdf, spec.domain), target_for(spec.name, spec.alpha))
    assert check.passed, check.summary


def test_names_as_users_write_them():
    assert target_for("tent") == target_for("square_to_tent") == target_for(" square_to_tent ")
    assert target_for("beckmann:0.3") == target_for("square_to_beckmann", 0.3) == target_for("beckmann:0.3", 0.3)
    assert target_for("beckmann:0.3").label == "square_to_beckmann's D(m) cos(theta_m), Beckmann alpha=0.3"
    for unknown in ("user warp", "uniform_disk_concentric", "square_to_uniform_cone", "tent:0.3", "Tent"):
        assert target_for(unknown) is None
    with pytest.raises(ValueError, match="roughness"):
        target_for("beckmann")
    with pytest.raises(ValueError, match="alpha=0.3, and alpha=0.5"):
        target_for("beckmann:0.3", 0.5)
    assert set(KNOWN) == {s.name for s in SUITE}
