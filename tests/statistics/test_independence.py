"""The batch-independence statistic: silent on independent batches of every kind the harness meets
(Gaussian, binary occlusion at few samples, neighbours correlated by a pixel filter, small images), loud on
repeated and strongly correlated ones."""
import numpy as np
import pytest
from scipy.ndimage import uniform_filter

from harness.statistics.independence import batch_dependence

K = 8


def _gaussian(rng, size=64):
    return rng.normal(size=(K, size, size, 3)) + 5.0


def _occlusion(rng, size=64, spp=32):
    """Binary estimates at `spp` samples, a quarter of the image without noise (fully visible)."""
    p = rng.random((size, size, 1)) * np.ones((1, 1, 3))
    p[: size // 4] = 1.0
    return rng.binomial(spp, p, size=(K, size, size, 3)) / spp


def _filtered(rng, size=64):
    """Neighbouring pixels share samples, as through a 3x3 pixel filter."""
    return uniform_filter(rng.normal(size=(K, size, size, 3)), size=(1, 3, 3, 1)) + 1.0


def _grey(rng, size=64, spp=4):
    x = rng.binomial(spp, rng.random((size, size)), size=(K, size, size)) / spp
    return np.repeat(x[..., None], 3, axis=-1)


KINDS = {"gaussian": _gaussian, "occlusion": _occlusion, "filtered": _filtered, "grey": _grey,
         "small": lambda rng: _gaussian(rng, 16), "tiny": lambda rng: _occlusion(rng, 8, 4)}


@pytest.mark.parametrize("kind", KINDS)
def test_independent_batches_are_never_called_dependent(kind):
    rng = np.random.default_rng(11)
    found = [batch_dependence(KINDS[kind](rng)) for _ in range(60)]
    assert not any(d.dependent for d in found)
    assert max(d.correlation for d in found) < 0.2  # about -1/7 for independent batches


def test_the_p_value_is_near_its_level_for_independent_gaussian_batches():
    rng = np.random.default_rng(3)
    p = np.array([batch_dependence(_gaussian(rng, 32)).p_value for _ in range(200)])
    assert 0.01 <= np.mean(p < 0.05) <= 0.11  # Bonferroni over 28 pairs: at most the level


def _repeat_pair(x):
    x = x.copy()
    x[5] = x[3]
    return x


def _repeat_half(x):
    x = x.copy()
    x[4:] = x[:4]
    return x


def _share_half(x):
    """Batch 1 takes half its samples from batch 2: residual correlation about 0.5."""
    x = x.copy()
    x[1] = 0.5 * (x[1] + x[2])
    return x


@pytest.mark.parametrize("defect", [_repeat_pair, _repeat_half, _share_half])
@pytest.mark.parametrize("kind", ["gaussian", "occlusion", "filtered"])
def test_repeated_or_shared_batches_are_dependent(defect, kind):
    d = batch_dependence(defect(KINDS[kind](np.random.default_rng(5))))
    assert d.dependent and d.p_value < 1e-10
    assert d.correlation > (0.4 if defect is _share_half else 0.99)


def test_a_repeated_pair_is_found_in_a_32_pixel_image():
    d = batch_dependence(_repeat_pair(_occlusion(np.random.default_rng(2), 32)))
    assert d.dependent and d.pair == (3, 5)


def test_batches_all_alike_vary_nowhere():
    x = _occlusion(np.random.default_rng(1))
    d = batch_dependence(np.repeat(x[:1], K, axis=0))
    assert d.varying == 0 and not d.dependent  # judged by the comparison, against the other side


def test_float_rounding_is_no_variation():
    x = np.repeat(_gaussian(np.random.default_rng(4))[:1], K, axis=0)
    x = x * (1 + 1e-7 * np.random.default_rng(5).standard_normal(x.shape))
    assert batch_dependence(x).varying == 0


def test_too_few_batches_or_non_finite_values_give_no_evidence():
    x = _gaussian(np.random.default_rng(6))
    assert batch_dependence(x[:2]) is None
    x[0, 3, 3, 1] = np.nan
    assert batch_dependence(x) is None
