"""Error metrics: FLIP is safe on any reference magnitude."""
import numpy as np
import pytest

from harness.comparison.metrics import flip_map, image_metrics


@pytest.mark.parametrize("scale", [1e-30, 1e-6, 1e6])
def test_hdr_flip_does_not_depend_on_a_common_scale(scale):
    """HDR-FLIP places its exposures by the reference: scaling both images changes nothing, and a
    reference of 1e-30 (which made flip_evaluator exit the process) is just another scale."""
    rng = np.random.default_rng(0)
    ref = rng.random((16, 16, 3)).astype(np.float32) * 3
    test = ref * 1.05
    assert flip_map(test * scale, ref * scale)[1] == pytest.approx(flip_map(test, ref)[1], rel=1e-4)


def test_hdr_flip_of_a_black_reference_is_nan_not_a_crash():
    error, mean = flip_map(np.ones((8, 8, 3)), np.zeros((8, 8, 3)))
    assert np.isnan(mean) and np.isnan(error).all()


def test_a_comparison_keeps_its_flip_map_and_its_picture_uses_it(monkeypatch):
    from harness.comparison.compare import compare_batches
    from harness.report import image_plots
    rng = np.random.default_rng(5)
    test, ref = 0.5 + 0.05 * rng.standard_normal((2, 4, 16, 16, 3))
    result = compare_batches(test, ref)
    assert result.flip_map.shape == (16, 16)
    assert np.array_equal(result.flip_map, flip_map(test.mean(axis=0, dtype=np.float64),
                                                    ref.mean(axis=0, dtype=np.float64))[0])

    def computed_again(*args, **kwargs):
        raise AssertionError("FLIP computed again for the picture")

    monkeypatch.setattr(image_plots, "flip_map", computed_again)
    assert image_plots.comparison_png(test.mean(axis=0), ref.mean(axis=0), result, False)[:4] == b"\x89PNG"


@pytest.mark.parametrize("shape", [(4, 32, 3), (32, 4, 3), (6, 6, 3), (2, 2, 3), (1, 5, 3)])
def test_metrics_of_an_image_under_seven_pixels_a_side_are_made_not_a_crash(shape):
    """SSIM's 7 x 7 window narrows to what the image holds (a 512 x 64 film at --resolution 32 is 32 x 4); under
    3 pixels it is NaN. The other metrics are computed as at any size."""
    rng = np.random.default_rng(3)
    a, b = rng.random(shape), rng.random(shape)
    m = image_metrics(a, b)
    assert np.isnan(m["ssim"]) == (min(shape[:2]) < 3)
    assert image_metrics(a, a)["ssim"] == pytest.approx(1.0) or min(shape[:2]) < 3
    assert np.isfinite(m["mse"]) and np.isfinite(m["flip_mean"])
