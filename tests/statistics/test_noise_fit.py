"""The fit of a single reference image's noise to its stated sample count: it accepts the count the image was
made with (several seeds, with and without a pixel filter's correlation), rejects a count four times off
either way, and flags an image that is noisy where the test engine's estimator is exact."""
import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

from harness.statistics.noise_fit import fit_noise, high_pass

H = W = 96
K, SPP = 8, 32


def _signal():
    yy, xx = np.mgrid[:H, :W]
    return 0.5 + 0.3 * np.sin(xx / 20.0) * np.cos(yy / 17.0), 0.2 + 0.3 * xx / W


def _image(rng, samples, blur=False, exact_left=False):
    signal, sigma = _signal()
    noise = rng.normal(size=(H, W)) * sigma / np.sqrt(samples)
    if blur:  # a pixel filter: neighbours share samples
        noise = 2.0 * gaussian_filter(noise, 0.7)
    if exact_left:
        noise[:, : W // 2] = 0.0
    return np.repeat((signal + noise)[..., None], 3, axis=-1)


def _fit(seed, rendered, stated, blur=False, exact_left=False, noisy_reference=True):
    rng = np.random.default_rng(seed)
    batches = np.stack([_image(rng, SPP, blur, exact_left) for _ in range(K)])
    image = _image(rng, rendered, blur, exact_left=exact_left and not noisy_reference)
    return fit_noise(batches, SPP, image, stated)


def test_the_high_pass_removes_a_linear_ramp():
    yy, xx = np.mgrid[:8, :8]
    np.testing.assert_allclose(high_pass(0.3 * xx + 0.2 * yy + 1.0), 0.0, atol=1e-12)


@pytest.mark.parametrize("blur", [False, True], ids=["independent pixels", "filtered"])
@pytest.mark.parametrize("seed", range(5))
def test_the_stated_count_fits_an_image_made_with_it(seed, blur):
    fit = _fit(seed, 256, 256, blur)
    assert fit.fits, fit.summary
    assert fit.noise_where_exact == 0


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("rendered, stated", [(64, 256), (1024, 256)], ids=["noisier", "cleaner"])
def test_a_count_four_times_off_does_not_fit(seed, rendered, stated):
    fit = _fit(seed, rendered, stated)
    assert not fit.fits, fit.summary
    assert fit.low <= stated / rendered <= fit.high


def test_noise_where_the_test_engine_is_exact_is_flagged():
    fit = _fit(0, 256, 256, exact_left=True)
    assert fit.noise_where_exact > 0 and not fit.fits
    assert "another estimator" in fit.summary


def test_an_exact_region_exact_in_both_is_no_evidence_against_the_count():
    fit = _fit(1, 256, 256, exact_left=True, noisy_reference=False)
    assert fit.noise_where_exact == 0 and fit.fits, fit.summary
