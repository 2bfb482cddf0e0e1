"""The pilot's estimate of the rounding noncentrality (harness/warps/bins.py, pilot_noncentrality), which spares
the cubature of every cell edge's strip where it is far below the limit: it tracks the cubature's figure, the
cells it gives are those the cubature gives, and a lobe whose float32 rounding does matter still gets fewer
cells."""
import numpy as np
import pytest

from harness.statistics.constants import FLOAT32_QUANTUM, HISTOGRAM_RES, ROUNDING_NONCENTRALITY, WARP_SAMPLES
from harness.warps import bins as wb
from harness.warps import checks as wc
from harness.warps.domains import get_domain
from tests.helpers.wrong_warps import beckmann_pdf, beckmann_sample

DOMAIN = get_domain("hemisphere")


def _pilot(alpha: float, seed: int = 5, n: int = 50_000):
    points = beckmann_sample(alpha)(np.random.default_rng(seed).random((n, 2))).astype(np.float32).astype(float)
    return DOMAIN.to_param(points)


def _cells(alpha: float) -> wb.Bins:
    s, t = _pilot(alpha)
    return wb.pilot_bins(wc.parameter_density(DOMAIN, beckmann_pdf(alpha)), s, t, HISTOGRAM_RES, WARP_SAMPLES,
                         FLOAT32_QUANTUM, DOMAIN.s_breaks)


@pytest.mark.parametrize("alpha", [0.3, 0.05, 0.01])
def test_the_estimate_tracks_the_cubature(alpha):
    s, _ = _pilot(alpha)
    edges = wb._edges(wb._segment_quantiles(s, HISTOGRAM_RES, ()))
    density = wc.parameter_density(DOMAIN, beckmann_pdf(alpha))
    exact = wb.rounding_noncentrality(density, edges, 0, WARP_SAMPLES, FLOAT32_QUANTUM)
    estimate = wb.pilot_noncentrality(np.sort(s), edges, WARP_SAMPLES, FLOAT32_QUANTUM)
    assert exact > 0 and 0.5 < estimate / exact < 4.0  # within the screen's margin of 10, leaning high


@pytest.mark.parametrize("alpha", [1.0, 0.3])
def test_the_screened_cells_are_the_cubatures(alpha, monkeypatch):
    calls = []
    exact_noncentrality = wb.rounding_noncentrality
    monkeypatch.setattr(wb, "rounding_noncentrality", lambda *a: calls.append(1) or exact_noncentrality(*a))
    screened = _cells(alpha)
    assert not calls  # the screen spared every cubature
    monkeypatch.setattr(wb, "pilot_noncentrality", lambda *a: np.inf)  # every edge set through the cubature
    exact = _cells(alpha)
    assert calls and screened.limited_by is None
    assert np.array_equal(screened.s_edges, exact.s_edges) and np.array_equal(screened.t_edges, exact.t_edges)


def test_a_lobe_that_rounding_biases_still_gets_fewer_cells():
    s, _ = _pilot(0.001)
    full = wb._edges(wb._segment_quantiles(s, HISTOGRAM_RES, ()))
    assert wb.pilot_noncentrality(np.sort(s), full, WARP_SAMPLES, FLOAT32_QUANTUM) > ROUNDING_NONCENTRALITY
    cells = _cells(0.001)
    assert cells.shape[0] < HISTOGRAM_RES and "float32" in cells.limited_by
