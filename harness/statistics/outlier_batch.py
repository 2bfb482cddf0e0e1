"""Does one batch stand apart from the others? The image mean's test takes the spread of K batch means for the
noise of their mean, so a single wild batch (a firefly of 10^4 in one pixel, or of 10^38) widens the spread
by as much as it moves the mean, and the test cannot reject it: t stays near 1 however wild the batch.

Each batch's image mean is held against the other K - 1 batches': under the null, with batch means
Gaussian (a mean over every pixel and sample of the batch), (x_i - mean of the others) / (s_others sqrt(1 +
1 / (K - 1))) is Student's t with K - 2 degrees of freedom: the externally studentized residual, whose
largest over the batches is Grubbs' outlier test. The p-value is Bonferroni over batches and channels. Where
the other batches agree to float rounding, nothing says how far a batch may stray (a rare contribution that
one batch saw): no batch is judged there.

Public API::

    outlier = batch_outlier(batch_means)   # (K, C)
    outlier.batch, outlier.channel, outlier.t, outlier.p_value
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from harness.statistics.distributions import t_sf

FLOAT32_ROUNDOFF = 2.0 ** -24


@dataclass(frozen=True)
class BatchOutlier:
    """The batch whose image mean stands furthest from the others', in units of their spread."""

    batches: int
    batch: int
    channel: int
    #: The studentized residual and its p-value (Bonferroni over batches and channels).
    t: float
    p_value: float
    #: That batch's image mean, and the mean of the others'.
    value: float
    others: float

    def to_json(self) -> dict:
        return {"batches": self.batches, "batch": self.batch, "channel": self.channel, "t": self.t,
                "p_value": self.p_value, "value": self.value, "others": self.others}


def batch_outlier(batch_means: np.ndarray) -> BatchOutlier | None:
    """The most outlying of (K, C) batch image means; None for fewer than 4 batches or where no batch can be
    judged (the others agree to rounding everywhere). A non-finite batch is the finite check's."""
    x = np.asarray(batch_means, np.float64)
    k = x.shape[0]
    if k < 4 or not np.isfinite(x).all():
        return None
    # The others of each batch, taken apart for each (K is small): a sum of squares less one batch's share
    # would cancel to nothing beside a batch of 1e38.
    rest = np.stack([np.delete(x, i, axis=0) for i in range(k)])
    others = rest.mean(axis=1)
    s = rest.std(axis=1, ddof=1)
    deviation = x - others
    # The batch means are float64 sums of float32 pixels: below float32's unit roundoff of the values, a
    # spread is arithmetic, not noise.
    rounding = FLOAT32_ROUNDOFF * (np.abs(others) + float(np.median(np.abs(x))))
    judged = s > rounding
    if not judged.any():
        return None
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(judged, deviation / (s * np.sqrt(1.0 + 1.0 / (k - 1))), 0.0)
    i, c = np.unravel_index(int(np.argmax(np.abs(t))), t.shape)
    p = float(min(1.0, 2.0 * float(t_sf(abs(t[i, c]), k - 2)) * x.size))
    return BatchOutlier(k, int(i), int(c), float(t[i, c]), p, float(x[i, c]), float(others[i, c]))
