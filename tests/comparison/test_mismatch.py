"""The diagnosis of a failed comparison with one image: a zoom, a shift, a constant factor and a background
shown in one image only are each named (with their size), and an image that differs only by noise, or by a
change no simple transform explains, gets no diagnosis."""
import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

from harness.comparison.mismatch import _moved, diagnose

N = 96


def _scene():
    """A bright disk and a dimmer square on a grey floor: edges in both directions."""
    yy, xx = np.mgrid[:N, :N]
    img = np.full((N, N), 0.3)
    img[(yy - 40) ** 2 + (xx - 35) ** 2 < 15 ** 2] = 0.9
    img[60:80, 55:85] = 0.6
    return np.repeat(gaussian_filter(img, 0.7)[..., None], 3, axis=-1)


def test_a_zoom_is_found_with_its_size():
    text = diagnose(_scene(), _moved(_scene(), 1.02, 0.0, 0.0))
    assert text and "zoomed by 1.020" in text


def test_a_shift_is_found():
    text = diagnose(_scene(), _moved(_scene(), 1.0, 0.5, -0.75))
    assert text and "moved by (-0.75, +0.50) pixels" in text


def test_a_factor_is_found():
    assert "times 1.0500" in diagnose(_scene(), 1.05 * _scene())


def test_a_background_shown_in_one_image_only_is_found():
    tested = _scene()
    tested[:20] = 0.0
    image = _scene()
    image[:20] = 0.6
    assert "lit where the tested image is black on 21 %" in diagnose(tested, image)


@pytest.mark.parametrize("seed", range(3))
def test_noise_alone_gets_no_diagnosis(seed):
    noisy = _scene() + np.random.default_rng(seed).normal(0.0, 0.05, (N, N, 3))
    assert diagnose(_scene(), noisy) is None


def test_a_change_no_transform_explains_gets_none():
    other = _scene()
    other[10:30, 60:90] = 0.95  # a shape that is not in mcval's
    assert diagnose(_scene(), other) is None
