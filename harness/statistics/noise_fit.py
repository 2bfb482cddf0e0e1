"""Does a single reference image carry the noise its stated sample count implies?

A reference image from elsewhere (Nori's `ref/*.exr`, a colleague's render) comes without its variance. The
comparison models it as the test engine's own per-sample variance over the stated N samples; this module
measures how well that model fits the image.

The measurement works on a high-pass of the image (each pixel minus the mean of its four neighbours), which
removes the smooth signal. Against the test engine's K batches of s samples each:

    d_i = L(reference)_i - L(mean of batches)_i,     v_i = variance over batches of L(batch)_i,

and under the model E[d_i^2] = v_i (s / N + 1 / K): the image's own noise plus that of the batch mean. The
high-pass of every batch sees the same pixel filter as the reference does, so the correlation the filter puts
between neighbours is in v_i too. Pixels are taken on a lattice three apart (their high-passes share no
pixel) and where the signal's own high-pass is within FLAT_SIGMAS standard errors of 0 (an edge that both images place differently
would read as noise); a pixel without variance whose neighbours have some (all K batches missed a rare
contribution there) is left out. The reference's noise relative to the model is

    rho = (sum d^2 - sum v / K) / sum (v s / N),

1 when the stated N is right, N / N' for a reference of N' samples of the same estimator. Its interval comes
from the ratio sum d^2 / sum v (s/N + 1/K), F-distributed with Satterthwaite's degrees of freedom (the
numerator's over the pixels, the denominator's K - 1 per pixel). Noise where the test engine has none (its
estimator is exact there, the reference's is not) is infinite rho: the model cannot hold. A region is exact
where the batches' variance, averaged over a VARIANCE_WINDOW neighbourhood, is 0, so that a pixel where all
K batches missed a rare occluder is not taken for an exact one.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import uniform_filter

from harness.statistics.constants import ROUNDING_TOLERANCE
from harness.statistics.distributions import f_ppf

#: Spacing of the pixels the fit uses: high-passes three apart share no pixel.
LATTICE = 3
#: Side of the neighbourhood over which the batches' variance is averaged.
VARIANCE_WINDOW = 5
#: A fitted rho within this factor of 1 (its interval reaching [1/F, F]) is taken as the stated count.
FIT_TOLERANCE = 1.5
#: A pixel is flat where the high-pass of the batch mean is within this many of its standard errors of 0.
FLAT_SIGMAS = 5.0
#: Where the batches are exact, a high-pass above this fraction of the pixel's value is an edge, not flat.
EXACT_EDGE = 0.01
#: Two-sided confidence of the interval on rho.
CONFIDENCE = 0.99


@dataclass(frozen=True)
class NoiseFit:
    """The reference's noise against the model's, over `pixels` lattice pixels."""

    rho: float            # measured noise over the model's (1: the stated count fits)
    low: float            # CONFIDENCE interval of rho
    high: float
    pixels: int           # lattice pixels the fit used
    stated_spp: int
    #: Pixels of the fit where the test engine has no noise and the reference has some.
    noise_where_exact: int

    @property
    def fits(self) -> bool:
        """Whether the stated sample count is within FIT_TOLERANCE of what the image's noise says."""
        return bool(self.noise_where_exact == 0 and self.pixels > 0 and
                    self.low <= FIT_TOLERANCE and self.high >= 1.0 / FIT_TOLERANCE)

    @property
    def implied_spp(self) -> float:
        """The sample count of the test engine's estimator that gives the image's noise."""
        return self.stated_spp / self.rho if self.rho > 0 else float("inf")

    @property
    def summary(self) -> str:
        """One line: the measured ratio, its interval and what it implies."""
        if self.pixels == 0:
            return "no flat pixels to measure the reference's noise on"
        if self.noise_where_exact:
            return (f"the reference is noisy on {self.noise_where_exact} of {self.pixels} measured pixels where the "
                    "test engine's estimator has no noise: it was made with another estimator")
        implied = "no noise" if self.rho <= 0 else f"about {self.implied_spp:.3g} spp"
        return (f"reference noise over the model ({self.stated_spp} spp of the test engine's estimator): "
                f"{self.rho:.3g} [{self.low:.3g}, {self.high:.3g}] on {self.pixels} flat pixels, i.e. {implied}")

    def to_json(self) -> dict:
        return {"rho": float(self.rho), "low": float(self.low), "high": float(self.high), "pixels": self.pixels,
                "stated_spp": self.stated_spp, "noise_where_exact": self.noise_where_exact, "fits": self.fits,
                "summary": self.summary}


def high_pass(x: np.ndarray) -> np.ndarray:
    """(..., H, W) -> (..., H-2, W-2): each inner pixel minus the mean of its four neighbours."""
    inner = x[..., 1:-1, 1:-1]
    around = x[..., :-2, 1:-1] + x[..., 2:, 1:-1] + x[..., 1:-1, :-2] + x[..., 1:-1, 2:]
    return inner - 0.25 * around


def _satterthwaite(weights: np.ndarray) -> float:
    total, squares = float(weights.sum()), float(np.square(weights).sum())
    return total * total / squares if squares > 0 else 1.0


def fit_noise(batches: np.ndarray, spp: int, image: np.ndarray, image_spp: int) -> NoiseFit:
    """The fit of `image` ((H, W, 3), said to hold `image_spp` samples) against the test engine's
    (K, H, W, 3) `batches` of `spp` samples each; see the module docstring. Channels are averaged first
    (a grey image's three channels are one measurement)."""
    b = np.asarray(batches, np.float64).mean(axis=-1)
    r = np.asarray(image, np.float64).mean(axis=-1)
    k = b.shape[0]
    lb = high_pass(b)
    per_pixel = lb.var(axis=0, ddof=1)
    v = per_pixel[::LATTICE, ::LATTICE]
    # Averaged over a neighbourhood, the variance tells an exact region from a pixel whose K batches all
    # missed a rare occluder (no variance of its own, its neighbours have some): the latter is left out.
    near = uniform_filter(per_pixel, VARIANCE_WINDOW, mode="nearest")[::LATTICE, ::LATTICE]
    signal = lb.mean(axis=0)[::LATTICE, ::LATTICE]
    lr = high_pass(r)[::LATTICE, ::LATTICE]
    d = lr - signal
    # Five standard errors: an edge stands out, while the noise of the batch mean (also in d) is hardly cut.
    # Where the batches have no variance, their high-pass is exact: flat unless it is an edge (a step of more
    # than EXACT_EDGE of the pixel's value).
    level = np.abs(r[1:-1, 1:-1][::LATTICE, ::LATTICE])
    flat = np.isfinite(d) & np.isfinite(v) & np.where(v > 0, np.square(signal) <= FLAT_SIGMAS ** 2 * v / k,
                                                      (near == 0) & (np.abs(signal) <= EXACT_EDGE * level))
    d, v = d[flat], v[flat]
    # Float32 sums scatter an exact value by a few ulps: that is no noise.
    rounding = ROUNDING_TOLERANCE * (level[flat] + np.abs(signal[flat]))
    exact = int(np.count_nonzero((v == 0) & (np.abs(d) > rounding)))
    own, model = v / k, v * spp / image_spp
    if d.size == 0 or model.sum() == 0:
        rho = float("inf") if exact else 1.0
        return NoiseFit(rho, rho, rho, int(d.size), image_spp, exact)
    ratio = float(np.square(d).sum() / (own + model).sum())
    nu1 = _satterthwaite(own + model)
    nu2 = (k - 1) * _satterthwaite(v)
    tail = (1.0 - CONFIDENCE) / 2.0
    low_ratio = ratio / f_ppf(1.0 - tail, nu1, nu2)
    high_ratio = ratio / f_ppf(tail, nu1, nu2)
    share = float(own.sum() / model.sum())  # E[ratio] = (rho + share) / (1 + share)

    def to_rho(x: float) -> float:
        return max(0.0, x * (1.0 + share) - share)

    return NoiseFit(to_rho(ratio), to_rho(low_ratio), to_rho(high_ratio), int(d.size), image_spp, exact)


def local_variance(batches: np.ndarray, image: np.ndarray, window: int = VARIANCE_WINDOW) -> np.ndarray:
    """(H, W, 3): the variance of each pixel of `image` as its own neighbourhood shows it, per channel.

    The squared high-pass difference d^2 (module docstring), less the batch mean's share (what is left, clipped
    at 0: an upper estimate), averaged over a `window` neighbourhood and divided by the high-pass's gain on this noise (its variance over the pixel's,
    measured on the batches, whose pixel filter is the image's). It sees noise the model cannot: a rare
    contribution all K batches missed, a reference made with a noisier estimator. Edge pixels take their
    inner neighbour's value."""
    b = np.asarray(batches, np.float64)
    k = b.shape[0]
    lb = high_pass(np.moveaxis(b, -1, 1))                      # (K, 3, H-2, W-2)
    d = high_pass(np.moveaxis(np.asarray(image, np.float64), -1, 0)) - lb.mean(axis=0)
    v = lb.var(axis=0, ddof=1)
    pixel_var = np.moveaxis(b, -1, 1)[..., 1:-1, 1:-1].var(axis=0, ddof=1)
    total = float(pixel_var.sum())
    gain = float(v.sum()) / total if total > 0 else 1.25      # 1 + 4/16 for independent pixels
    size = (1, window, window)
    with np.errstate(invalid="ignore", over="ignore"):
        # Clipped per pixel before the average: an edge's large batch variance must not cancel its neighbours'.
        excess = np.maximum(np.nan_to_num(np.square(d) - v / k, nan=np.inf, posinf=np.inf), 0.0)
        inner = uniform_filter(excess, size, mode="nearest") / gain
    return np.moveaxis(np.pad(inner, ((0, 0), (1, 1), (1, 1)), mode="edge"), 0, -1)
