"""The per-test level of a family of Welch tests (harness.statistics.family_level) against its definition and
against simulation: noiseless elements do not count, correlated channels count less than three, tests
shrunk by the rounding floor count by how often they can still reject."""
import numpy as np
import pytest
from scipy import stats as sps

from harness.comparison.compare import compare_batches
from harness.statistics.family_level import channel_correlation, channel_union, element_rates, family_level
from harness.statistics.constants import SIGNIFICANCE, sidak_level


def test_independent_tests_get_sidaks_level():
    dof, inflation = np.full((40, 3), 7.0), np.ones((40, 3))
    assert family_level(0.1, dof, inflation) == pytest.approx(sidak_level(0.1, 120), rel=1e-6)


def test_noiseless_elements_do_not_count():
    inflation = np.ones((50, 3))
    inflation[20:] = np.inf  # 30 elements without noise on either side
    assert family_level(0.1, np.full((50, 3), 7.0), inflation) == pytest.approx(sidak_level(0.1, 60), rel=1e-6)


def test_no_live_element_gives_the_family_level():
    assert family_level(0.05, np.full((4, 3), 7.0), np.full((4, 3), np.inf)) == 0.05


def test_identical_channels_count_once():
    dof, inflation = np.full((100, 3), 7.0), np.ones((100, 3))
    level = family_level(0.1, dof, inflation, rho=0.999)
    assert sidak_level(0.1, 300) < level
    assert level == pytest.approx(sidak_level(0.1, 100), rel=0.1)


@pytest.mark.parametrize("rho", [0.3, 0.8, 0.95])
def test_channel_union_matches_simulation(rho):
    rng = np.random.default_rng(1)
    level, n = 0.01, 2_000_000
    shared = rng.standard_normal(n)
    z = np.sqrt(rho) * shared[:, None] + np.sqrt(1 - rho) * rng.standard_normal((n, 3))
    simulated = np.mean(np.abs(z).max(axis=1) > sps.norm.isf(level / 2)) / level
    assert channel_union(level, 3, rho) == pytest.approx(simulated, rel=0.02)
    assert 1.0 <= channel_union(level, 3, rho) <= 3.0


def test_channel_union_limits():
    assert channel_union(1e-6, 3, 0.0) == 3.0
    assert channel_union(1e-6, 1, 0.9) == 1.0
    assert channel_union(1e-6, 3, 0.999) < 1.3


def test_floored_tests_reject_less_than_their_level():
    rates = element_rates(1e-3, np.array([7.0, 7.0, 7.0, 7.0]), np.array([1.0, 1.1, 3.0, np.inf]))
    assert rates[0] == pytest.approx(1e-3, rel=1e-9)
    assert rates[0] > rates[1] > rates[2] > rates[3] == 0.0
    # By simulation: a t(7) statistic shrunk by 1.1 exceeds the critical value of 1e-3 this often.
    t = sps.t.rvs(7, size=4_000_000, random_state=np.random.default_rng(2)) / 1.1
    assert rates[1] == pytest.approx(np.mean(np.abs(t) > sps.t.isf(5e-4, 7)), rel=0.05)


def test_floored_family_is_given_a_higher_level():
    dof = np.full((200, 3), 7.0)
    assert family_level(0.1, dof, np.full((200, 3), 2.0)) > 5 * sidak_level(0.1, 600)
    assert family_level(0.1, dof, np.full((200, 3), 2.0)) <= 0.1


def test_channel_correlation_of_statistics():
    rng = np.random.default_rng(3)
    shared = rng.standard_normal((5000, 1))
    t = np.sqrt(0.7) * shared + np.sqrt(0.3) * rng.standard_normal((5000, 3))
    assert channel_correlation(t, np.ones(5000, bool)) == pytest.approx(0.7, abs=0.03)
    assert channel_correlation(t[:5], np.ones(5, bool)) == 0.0  # too few to tell
    # A few heavily biased elements (the alternative) do not decide it.
    t[:20, 0] += 100.0
    assert channel_correlation(t, np.ones(5000, bool)) == pytest.approx(0.7, abs=0.05)


def test_grey_image_is_tested_per_pixel_not_per_channel():
    rng = np.random.default_rng(4)
    grey = lambda k: np.repeat(0.5 + 0.01 * rng.standard_normal((k, 16, 16, 1)), 3, axis=-1)
    result = compare_batches(grey(8), grey(16))
    per_scale = sidak_level(SIGNIFICANCE, 3)
    assert result.scales[0].level == pytest.approx(sidak_level(per_scale, 256), rel=0.1)


def test_a_flat_image_with_one_noisy_pixel_tests_that_pixel_at_the_scale_level():
    rng = np.random.default_rng(5)
    a, b = np.full((8, 16, 16, 3), 0.5), np.full((16, 16, 16, 3), 0.5)
    a[:, 3, 4, :] += 0.01 * rng.standard_normal((8, 1))
    b[:, 3, 4, :] += 0.01 * rng.standard_normal((16, 1))
    result = compare_batches(a, b)
    # Only one pixel can reject (its channels identical): it gets the whole pixel-scale level.
    assert result.scales[0].level == pytest.approx(sidak_level(SIGNIFICANCE, 3), rel=0.05)


def test_channel_correlation_is_the_low_end_of_fishers_interval():
    rng = np.random.default_rng(6)
    shared = rng.standard_normal((40, 1))
    t = np.sqrt(0.6) * shared + np.sqrt(0.4) * rng.standard_normal((40, 3))
    c = np.corrcoef(t, rowvar=False)
    r = np.mean([c[0, 1], c[0, 2], c[1, 2]])
    expected = np.tanh(np.arctanh(r) - 2.0 / np.sqrt(40 - 3))
    assert 0 < expected < r
    assert channel_correlation(t, np.ones(40, bool)) == pytest.approx(expected, rel=1e-9)
    # Ten elements are enough to estimate it; nine are not.
    ten = t[:10]
    c10 = np.corrcoef(ten, rowvar=False)
    r10 = np.mean([c10[0, 1], c10[0, 2], c10[1, 2]])
    assert channel_correlation(ten, np.ones(10, bool)) == pytest.approx(
        max(0.0, np.tanh(np.arctanh(r10) - 2.0 / np.sqrt(7))), abs=1e-12)
    assert channel_correlation(t[:9], np.ones(9, bool)) == 0.0


def test_channel_correlation_of_one_channel_or_identical_channels():
    rng = np.random.default_rng(7)
    t = rng.standard_normal((50, 1))
    assert channel_correlation(t, np.ones(50, bool)) == 0.0  # one channel: nothing to correlate
    assert channel_correlation(np.repeat(t[:3], 3, axis=1), np.ones(3, bool)) == 1.0
    two = np.hstack([t, -t + 0.1 * rng.standard_normal((50, 1))])  # anti-correlated: clipped at 0
    assert channel_correlation(two, np.ones(50, bool)) == 0.0
    # Statistics beyond |t| = 4 count as 4: two channels at opposite extremes stay uncorrelated.
    wide = np.hstack([t, t])
    wide[:, 1] += rng.standard_normal(50)
    clipped = np.clip(wide, -4, 4)
    wide[0] = [50.0, -50.0]
    clipped[0] = [4.0, -4.0]
    r = np.corrcoef(clipped, rowvar=False)[0, 1]
    assert channel_correlation(wide, np.ones(50, bool)) == pytest.approx(
        max(0.0, np.tanh(np.arctanh(r) - 2.0 / np.sqrt(47))), rel=1e-9)


# --- corners found by mutation testing -------------------------------------------------------------

def _exact_level(level_family, dof, inflation, share=1.0):
    """The defining equation solved directly: every live test's rate summed, no sampling."""
    from scipy.optimize import brentq

    live = np.isfinite(inflation)
    d, f = dof[live], inflation[live]

    def excess(log_level):
        rates = np.minimum(element_rates(np.exp(log_level), d, f) * share, 1.0)
        return -np.expm1(np.sum(np.log1p(-rates))) - level_family

    if excess(np.log(level_family)) <= 0:  # even at the family's level they reject less often
        return level_family
    return float(np.exp(brentq(excess, np.log(1e-14), np.log(level_family), xtol=1e-12)))


@pytest.mark.parametrize("inflation", [[1.0, 1.7], [2.5], [1.0, 1.0, 3.0, 1.2, np.inf]])
def test_small_families_match_the_defining_equation(inflation):
    inflation = np.array(inflation)[:, None]
    dof = np.full(inflation.shape, 9.0)
    assert family_level(0.2, dof, inflation) == pytest.approx(_exact_level(0.2, dof, inflation), rel=1e-6)


def test_large_floored_families_are_summed_within_a_percent():
    rng = np.random.default_rng(6)
    inflation = 1.0 + rng.exponential(0.5, (3000, 1))  # more than SAMPLED tests shrunk by the floor
    dof = rng.uniform(7, 30, (3000, 1))
    assert family_level(0.1, dof, inflation) == pytest.approx(_exact_level(0.1, dof, inflation), rel=0.01)


def test_scalar_and_single_element_inputs():
    assert family_level(0.05, 7.0, 1.0) == pytest.approx(0.05)
    # One element of three identical channels (the image scale of a grey image) is one test.
    assert family_level(0.1, np.full(3, 7.0), np.ones(3), rho=1.0) == pytest.approx(0.1, rel=1e-6)
    assert family_level(0.1, np.full(3, 7.0), np.ones(3), rho=0.0) == pytest.approx(sidak_level(0.1, 3), rel=1e-6)


def test_correlation_corners():
    rng = np.random.default_rng(7)
    # One channel (the last axis) gives nothing to correlate, whatever the other axes.
    assert channel_correlation(rng.standard_normal((20, 3, 1)), np.ones((20, 3), bool)) == 0.0
    # Constant channels have no correlation to estimate.
    constant = np.tile([1.0, 2.0, 3.0], (50, 1))
    assert channel_correlation(constant, np.ones(50, bool)) == 0.0
    # Proportional but not identical channels: correlation 1, stated just below it.
    x = rng.standard_normal((1000, 1))
    value = channel_correlation(np.hstack([x, 0.5 * x, 0.25 * x]), np.ones(1000, bool))
    assert 0.99 < value < 1.0


def test_two_correlated_channels_count_less_than_two():
    assert 1.0 < channel_union(0.01, 2, 0.9) < 1.9
