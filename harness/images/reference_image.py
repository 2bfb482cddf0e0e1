"""A reference that is one image from elsewhere (--reference-image FILE.exr --reference-spp N): Nori's
`ref/*.exr`, an image a course hands out. It has no batches, so its variance is a model, stated with the
verdict, with the evidence that the image fits it (harness/statistics/noise_fit.py):

- "stated" (the default): the test engine's own per-sample variance over N samples. A reference whose noise
  does not fit N is reported as such and does not pass.
- "measured": the same per-sample variance scaled by the noise the image shows (the fit's upper bound, so
  the reference's noise is never understated); for an image whose N is unknown or wrong.

Either way the modelled variance is a multiple c of the test engine's variance of its mean, c = K s rho / N
(K batches of s samples), so the comparison gives it to the test side, (1 + c) times its own variance with
its own degrees of freedom (Welch's test on two estimates of one variance would count them twice). The image's
side holds what its own neighbourhood shows beyond the model (noise_fit.local_variance): about nothing under
the model, and the variance of a rare contribution that all of the test engine's batches missed (where those
agree exactly, the pixel's own deviation: one pixel there is no evidence either way).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from harness.comparison.summary import Summary, tile_means
from harness.exr import ExrError, read_image
from harness.statistics.constants import MISSED_CONTRIBUTION, ROUNDING_TOLERANCE
from harness.statistics.noise_fit import VARIANCE_WINDOW, NoiseFit, fit_noise, local_variance
from harness.statistics.welch import BatchStats

NOISE_MODELS = ("stated", "measured")
#: Degrees of freedom of a variance the image's neighbourhood shows (harness.statistics.noise_fit.local_variance).
LOCAL_DOF = float(VARIANCE_WINDOW ** 2 - 1)


@dataclass(frozen=True)
class ReferenceImage:
    """The image of --reference-image, its stated samples per pixel and the noise model."""

    path: Path
    spp: int
    noise: str = "stated"

    def read(self) -> np.ndarray:
        """The (H, W, 3) image; ValueError naming the file and what is wrong with it."""
        try:
            image, _ = read_image(self.path)
        except (ExrError, OSError) as e:
            raise ValueError(f"--reference-image {self.path}: {e}") from None
        bad = int(np.count_nonzero(~np.isfinite(image)))
        if bad:
            raise ValueError(f"--reference-image {self.path}: {bad} values are NaN or infinite")
        return np.asarray(image, np.float64)

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) of the image."""
        h, w = self.read().shape[:2]
        return w, h

    def describe(self) -> str:
        return f"reference image {self.path} ({self.spp} spp, noise model: {self.noise})"


@dataclass
class ImageComparisonInputs:
    """What a comparison against the image needs: the two summaries, and the noise fit behind them."""

    test: Summary        # the test engine's, its variances times (1 + c)
    reference: Summary   # the image, with the variance it shows beyond the model
    fit: NoiseFit
    factor: float        # c: the reference's variance over the test engine's variance of its mean


def _scaled(stats: BatchStats, by: float) -> BatchStats:
    return BatchStats(stats.mean, np.asarray(stats.var_of_mean) * by, stats.k, stats.dof)


def against_image(ref: ReferenceImage, image: np.ndarray, test: Summary, batches: np.ndarray,
                  spp: int) -> ImageComparisonInputs:
    """The summaries that compare the test engine's `batches` ((K, H, W, 3) of `spp` samples, summarised as
    `test`) with `image` under `ref`'s noise model. ValueError if the sizes differ."""
    if image.shape != test.pixel.mean.shape:
        h, w = test.pixel.mean.shape[:2]
        raise ValueError(f"--reference-image {ref.path}: {image.shape[1]}x{image.shape[0]} pixels, the render "
                         f"{w}x{h}")
    fit = fit_noise(batches, spp, image, ref.spp)
    k = test.image.k
    rho = 1.0 if ref.noise == "stated" else (fit.high if np.isfinite(fit.high) else 1.0)
    factor = k * spp * max(rho, 0.0) / ref.spp
    own = np.asarray(test.pixel.var_of_mean)
    shown = local_variance(batches, image)
    # A pixel variance of K batches is far too small where few of them saw a rare contribution; the image's
    # neighbourhood predicts it too (scaled from N samples to K s), and where the tested one is far below that
    # prediction (as harness.statistics.welch.sample_floor judges it), the prediction is taken.
    predicted = shown * ref.spp / (k * spp)
    missed = own < MISSED_CONTRIBUTION * predicted
    pixel = BatchStats(test.pixel.mean, np.where(missed, predicted, own) * (1.0 + factor), k, test.pixel.dof)
    inflated = Summary(pixel, _scaled(test.tile, 1.0 + factor), _scaled(test.image, 1.0 + factor),
                       test.tile_size, test.minimum)
    # What the image's own neighbourhood shows beyond the model (a rare contribution the tested batches all missed)
    # is the image's side of the variance; under the model it is about 0.
    # Where all K batches agree (to float32 rounding) they cannot say whether the image saw a rare contribution
    # there or is wrong: the pixel's deviation is its variance (the tile and image scales still see a bias).
    agree = own <= np.square(ROUNDING_TOLERANCE * np.abs(np.asarray(test.pixel.mean)))
    shown = np.where(agree, np.maximum(shown, np.square(image - test.pixel.mean)), shown)
    excess = np.maximum(shown - factor * own, 0.0)
    t, (h, w) = test.tile_size, image.shape[:2]
    per_tile = tile_means(excess[None], t)[0] / tile_means(np.ones((1, h, w, 1)), t)[0] / (t * t)
    reference = Summary(BatchStats(image, excess, k, np.full(excess.shape, LOCAL_DOF)),
                        BatchStats(tile_means(image[None], t)[0], per_tile, k),
                        BatchStats(image.mean(axis=(0, 1)), excess.mean(axis=(0, 1)) / (h * w), k), t)
    return ImageComparisonInputs(inflated, reference, fit, factor)


def fit_verdict(ref: ReferenceImage, fit: NoiseFit) -> str | None:
    """Why the image cannot be compared under its model (one line), or None when it can."""
    if fit.noise_where_exact:
        return f"{fit.summary}; no sample count of the test engine's estimator models its noise"
    if ref.noise == "stated" and not fit.fits:
        return f"the reference's noise does not fit its stated {ref.spp} spp: {fit.summary}"
    return None
