"""Comparing two engines' batch renders: Welch's t-test at three scales, and error metrics.

Public API::

    result = compare_batches(test, reference)   # (K, H, W, 3) arrays each
    result.passed, result.scales, result.metrics

Each engine renders K independent batches, so any statistic (a pixel, a tile
mean, the image mean) is a mean of K independent values per engine, and Welch's
t-test on them is valid whatever the filter or sampler correlation (Jung,
Hanika, Dachsbacher, JCGT 2020). The false-alarm rate `alpha` is split evenly
(Sidak) over the three scales, so a global bias (a missing 1/pi) and a local one
(a shadow in the wrong place) are both caught; within a scale the level of each
test is the one that gives the scale its share (`harness.statistics.family_level`): elements
without noise on either side cannot reject and do not count, elements shrunk by
the rounding floor count by how often they can still reject, and the three
channels count by their correlation (once for a grey image). Pixel variances
are moderated towards their 3x3 neighbourhood's (empirical Bayes,
`harness.statistics.welch.moderate`), never below their own; tile and image means keep
their own. At every scale, a variance far below what the better-sampled side
predicts for its sample count (all K batches missed a rare contribution) takes
that prediction (`harness.statistics.welch.sample_floor`). Each scale then rejects a correct
renderer at its stated level (tests/images/test_calibration.py). `detectable_bias`
and `detectable_tile_bias` are the relative biases found half of the time
(noncentral t at the Welch dof).
A render can be reduced to its `Summary` first (what references store).

Before any statistics, both sides are checked for NaN, +Inf and -Inf, and for
negative values unless the image is signed (normals): any such pixel fails the
comparison through its own check (`Comparison.finite`), and the statistics treat
a non-finite input as a certain rejection, never as agreement. Each side whose
batches are at hand is also checked for batches that are not independent (all
alike where the other side's vary, or a pair far more alike than chance:
`Comparison.independence`), which would make the spread the tests divide by too
small; that too fails the comparison through its own check.
"""
from __future__ import annotations

from functools import cache

import numpy as np

from harness.statistics.detectable_bias import half_power_bias
from harness.statistics.family_level import channel_correlation, family_level
from harness.comparison.finite import FiniteCheck, damage_of_summary, per_pixel
from harness.comparison.independence_check import IndependenceCheck, constant_image
from harness.comparison.metrics import image_metrics
from harness.comparison.outcome import SCALES, Comparison, ScaleTest
from harness.comparison.outlier_check import OutlierCheck
from harness.comparison.summary import Summary, summarize
from harness.comparison.variance_check import VarianceCheck
from harness.statistics.constants import (IMAGE_POWER_TARGET, INCONCLUSIVE_BIAS, POWER_TARGET, ROUNDING_TOLERANCE,
                                          SIGNIFICANCE, TILE_SIZE, sidak_level)
from harness.statistics.welch import BatchStats, moderate, sample_floor, welch_dof, welch_p_values

def _scale_test(name: str, a: BatchStats, b: BatchStats, noiseless: np.ndarray, level_family: float,
                shape: tuple[int, int], upsample: int, scale: float, rounding: float,
                rho: float | None = None, keep: dict[str, np.ndarray] | None = None) -> tuple[ScaleTest, float]:
    """The Welch tests of one scale at the level that gives them `level_family` together (`family_level`:
    `noiseless` elements, without noise on either side, cannot reject; the channels are correlated by
    `rho`, estimated from this scale's t statistics when None). Returns the test and that rho; `keep`, if
    given, receives the tests' standard errors and degrees of freedom ("se", "dof": for the power figures)."""
    p, t, se = welch_p_values(a, b, scale, rounding)
    dof = welch_dof(a, b)
    if keep is not None:
        keep.update(se=se, dof=dof)
    # A NaN p-value (a non-finite input) is no evidence of agreement: it counts as a certain rejection.
    p = np.where(np.isnan(p), 0.0, p)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        noise = np.sqrt(a.var_of_mean + b.var_of_mean)
        inflation = np.where(noiseless | ~(noise > 0), np.inf, se / np.where(noise > 0, noise, 1.0))
    live = np.isfinite(inflation) & np.isfinite(t)
    if rho is None:
        rho = channel_correlation(t, per_pixel(np.logical_and, live)) if t.ndim >= 2 else 0.0
    level = family_level(level_family, dof, np.where(np.isnan(inflation), 1.0, inflation), rho)
    pmin = per_pixel(np.minimum, p) if p.ndim == 3 else np.full((1, 1), p.min())
    idx = np.unravel_index(int(np.argmin(pmin)), pmin.shape)
    full = np.repeat(np.repeat(pmin, upsample, axis=0), upsample, axis=1)[: shape[0], : shape[1]]
    if full.shape != shape:
        full = np.full(shape, float(p.min()))
    return ScaleTest(scale=name, tests=int(p.size), level=level, min_p=float(p.min()),
                     failures=int(np.count_nonzero(p < level)),
                     worst=(int(idx[0]) * upsample, int(idx[1]) * upsample), p_map=full), rho


def _at_least_own(stats: BatchStats) -> BatchStats:
    """`moderate`, but never below the element's own variance: moderation that pulls a shadow-edge pixel's
    variance down to its quieter neighbours' made null renders reject (sphere on a plane: 0.045 at 0.01)."""
    moderated = moderate(stats)
    own = np.asarray(stats.var_of_mean)
    with np.errstate(invalid="ignore"):
        keep = own > moderated.var_of_mean
    dof = np.where(keep, float(stats.k - 1), np.broadcast_to(moderated.var_dof, own.shape))
    return BatchStats(stats.mean, np.where(keep, own, moderated.var_of_mean), stats.k, dof)


def _noiseless(a: BatchStats, b: BatchStats) -> np.ndarray:
    """Elements whose batches are constant on both sides (before moderation): t is 0 when they agree."""
    return (a.var_of_mean == 0) & (b.var_of_mean == 0)


def _no_signal(test: Summary, reference: Summary) -> str:
    """Why there is nothing to compare ("" when there is): both images 0 everywhere in every batch. Two images
    of one other value everywhere (a floor filling the frame under a uniform light) still show that value, and
    two different values fail at every scale."""
    if not (constant_image(test) and constant_image(reference)):
        return ""
    if float(test.pixel.mean.flat[0]) != 0.0 or float(reference.pixel.mean.flat[0]) != 0.0:
        return ""
    return ("no signal: both images are 0 everywhere in every batch (nothing in view is shaded: a camera "
            "facing away, a one-sided surface seen from behind?)")


@cache
def _metric_names() -> tuple[str, ...]:
    return tuple(image_metrics(np.ones((8, 8, 3)), np.ones((8, 8, 3))))


def _metrics(test: np.ndarray, reference: np.ndarray, signed: bool,
             maps: dict[str, np.ndarray] | None = None) -> dict[str, float]:
    """image_metrics, or NaN for every metric where they mean nothing or cannot be computed: a mean
    image with a non-finite pixel, or a radiance reference with no positive value (FLIP's HDR mode
    cannot place its exposures there and ends the process)."""
    if not (np.isfinite(test).all() and np.isfinite(reference).all()) or (not signed and not reference.max() > 0):
        return dict.fromkeys(_metric_names(), float("nan"))
    return image_metrics(test, reference, signed=signed, maps=maps)


def compare_summaries(test: Summary, reference: Summary, alpha: float = SIGNIFICANCE, signed: bool = False,
                      rounding: float = ROUNDING_TOLERANCE,
                      samples: tuple[int | None, int | None] = (None, None), metrics: bool = True,
                      power: bool = True, same_estimator: bool = False, tile_power: bool = True,
                      heavy_tail: str = "") -> Comparison:
    """compare_batches on summaries (see there). The finite check looks at the summaries: a non-finite
    mean or variance, a negative variance, and unless `signed` a negative value in any batch (the
    summary's minimum; the mean for a stored summary, which keeps no minimum).

    The verdict needs neither the error metrics nor the detectable biases, which cost most of a comparison
    (FLIP; a noncentral t per tile): with `metrics` False the metrics are left empty, with `power` False
    both detectable biases are NaN. Null and planted comparisons, which count rejections, skip them; with
    `tile_power` False only the tile's is (NaN), for callers that report the image's alone.
    `same_estimator`: the reference draws the test's estimator sample for sample, so that test batches all
    alike where the reference's vary fail as not independent (`IndependenceCheck`), and a per-sample variance
    beyond the noise fails (`VarianceCheck`, then a fourth member of the family beside the scales);
    `heavy_tail` says why its pixels' excess over the reference's neighbourhood is not tested there."""
    if test.pixel.mean.shape != reference.pixel.mean.shape or test.tile_size != reference.tile_size:
        raise ValueError(f"images differ in size: {test.pixel.mean.shape} and {reference.pixel.mean.shape}")
    finite = FiniteCheck(damage_of_summary(test, signed), damage_of_summary(reference, signed), signed)
    independence = IndependenceCheck.of(test, reference, same_estimator)
    outliers = OutlierCheck.of(test, reference)
    h, w = test.pixel.mean.shape[:2]
    # Against the same estimator the variance test is a verdict: a fourth member of the family, at a scale's share.
    judged_noise = same_estimator and None not in samples
    per_scale = sidak_level(alpha, len(SCALES) + judged_noise)
    variance = VarianceCheck.of(test, reference, samples, per_scale, same_estimator, heavy_tail)
    ref = reference.pixel.mean[np.isfinite(reference.pixel.mean)]
    magnitude = float(np.mean(np.abs(ref))) if ref.size else 0.0
    # Moderation is for the pixel scale, where the variances of K batches of a few samples scatter widely; a
    # tile or image mean sums 64 or more pixels and keeps its own variance (moderated, the tile tests came out
    # twice too conservative at 1e-3 on null renders). The sample floor is for every scale: an otherwise
    # noiseless tile whose one edge pixel missed its sliver in all K batches has no variance either.
    test_pixel, ref_pixel = sample_floor(_at_least_own(test.pixel), _at_least_own(reference.pixel), *samples,
                                         test.pixel, reference.pixel)
    test_tile, ref_tile = sample_floor(test.tile, reference.tile, *samples)
    test_image, ref_image = sample_floor(test.image, reference.image, *samples)
    tile_tests: dict[str, np.ndarray] = {}
    image_tests: dict[str, np.ndarray] = {}
    pixel, _ = _scale_test("pixel", test_pixel, ref_pixel, _noiseless(test.pixel, reference.pixel), per_scale,
                           (h, w), 1, magnitude, rounding)
    tile, rho = _scale_test("tile", test_tile, ref_tile, _noiseless(test.tile, reference.tile), per_scale, (h, w),
                            test.tile_size, magnitude, rounding, keep=tile_tests)
    # One image mean gives no correlation to estimate: its channels are taken to be as correlated as the tiles'.
    image, _ = _scale_test("image", test_image, ref_image, _noiseless(test.image, reference.image), per_scale,
                           (h, w), max(h, w), magnitude, rounding, rho, image_tests)
    scales = [pixel, tile, image]
    maps: dict[str, np.ndarray] = {}
    figures = _metrics(test.mean_image, reference.mean_image, signed, maps) if metrics else {}
    no_signal = _no_signal(test, reference)
    if not power:
        return Comparison(scales=scales, metrics=figures, detectable_bias=float("nan"),
                          batches=(test.image.k, reference.image.k), finite=finite, detectable_tile_bias=float("nan"),
                          detectable_bias_most=float("nan"), flip_map=maps.get("flip"), independence=independence,
                          variance=variance, outliers=outliers, inconclusive=no_signal)
    # The image-mean bias found half of the time, and the same for one tile (median over tiles).
    image_biases = half_power_bias(ref_image, image_tests["se"], image_tests["dof"], scales[2].level, rho,
                                   (IMAGE_POWER_TARGET, POWER_TARGET))
    detectable, detectable_most = map(float, image_biases[0])
    detectable_tile = float("nan")
    if tile_power:
        per_tile = half_power_bias(ref_tile, tile_tests["se"], tile_tests["dof"], scales[1].level, rho)
        per_tile = per_tile[np.isfinite(per_tile)]
        detectable_tile = float(np.median(per_tile)) if per_tile.size else float("inf")
    inconclusive = no_signal or (f"the comparison finds a bias of the image mean only from {detectable:.3g} on (half of "
                                 f"the time), above the {INCONCLUSIVE_BIAS:.0%} it must resolve"
                                 if not detectable <= INCONCLUSIVE_BIAS else "")
    return Comparison(scales=scales, metrics=figures, detectable_bias=detectable,
                      batches=(test.image.k, reference.image.k), finite=finite, detectable_tile_bias=detectable_tile,
                      detectable_bias_most=detectable_most, flip_map=maps.get("flip"), independence=independence,
                      variance=variance, outliers=outliers, inconclusive=inconclusive)


def compare_batches(test: np.ndarray, reference: np.ndarray, alpha: float = SIGNIFICANCE,
                    tile: int = TILE_SIZE, signed: bool = False, rounding: float = ROUNDING_TOLERANCE,
                    samples: tuple[int | None, int | None] = (None, None), same_estimator: bool = False) -> Comparison:
    """Compare (K1, H, W, 3) test batches against (K2, H, W, 3) reference batches.

    Fails if any scale rejects at the false-alarm rate `alpha`, or if either side holds
    a NaN, +Inf or -Inf in any batch, or a negative value unless `signed`. `signed`
    marks images with negative values (normals), for that check and the metrics;
    `rounding` is the relative precision of the values (float32 by default);
    `samples` the samples per pixel of each side's batches, which lets each
    side's variance floor the other's (`harness.statistics.welch.sample_floor`; None for
    an exact reference or an unknown count).
    """
    t, r = np.asarray(test), np.asarray(reference)
    if t.ndim != 4 or t.shape[1:] != r.shape[1:]:
        raise ValueError(f"expected two (K, H, W, 3) arrays of one image size, got {t.shape} and {r.shape}")
    return compare_summaries(summarize(t, tile), summarize(r, tile), alpha, signed, rounding, samples,
                             same_estimator=same_estimator)
