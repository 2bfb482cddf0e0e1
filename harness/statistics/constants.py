"""Statistical constants of the harness, named once, and the corrections built on them."""
from __future__ import annotations

#: Family-wise false-alarm rate of one whole run (all tests together).
SIGNIFICANCE = 0.01
#: Histogram cells expecting fewer samples than this are pooled before a chi-square test.
MIN_EXPECTED = 5.0
#: Samples drawn per warp for the goodness-of-fit and homogeneity tests.
WARP_SAMPLES = 1_000_000
#: Histogram resolution per axis of a warp's parameter square (odd: no cell edge on a symmetry axis).
HISTOGRAM_RES = 51
#: Spacing of float32 coordinates just above 1 (2^-23), the scale of every warp domain: a float32 sampler's
#: samples sit up to half of it away from where exact arithmetic would put them.
FLOAT32_QUANTUM = 2.0 ** -23
#: Histogram cells are coarsened until the rounding of float32 samples across their edges (uniform within
#: +-FLOAT32_QUANTUM/2) adds at most this much expected noncentrality to the chi-square statistic.
ROUNDING_NONCENTRALITY = 1.0
#: Power figures: the smallest planted defect a check detects in this fraction of replications.
POWER_TARGET = 0.9
#: Monte Carlo replications per candidate defect size when power is simulated.
POWER_REPLICATIONS = 200
#: How far the integral of a pdf over its domain may be from 1.
NORMALISATION_TOLERANCE = 1e-3
#: Relative agreement required between two implementations of the same pdf (float32 both).
PDF_RELATIVE_TOLERANCE = 1e-3
#: Densities below this carry no mass a test can see (4 pi x 1e-30 on the whole sphere): two pdfs that differ by
#: less agree, whatever their ratio. A float32 pdf underflows to 0 where a float64 closed form is still 1e-35.
PDF_ABSOLUTE_FLOOR = 1e-30
#: Slack on "unit length" and "inside the unit disk" for points rounded to float32.
UNIT_TOLERANCE = 1e-5
#: A sample this many float32 ulps of 1 (the scale of every warp domain) from the edge of its domain is on the
#: boundary: a pdf of 0 there is a warning (f/pdf is 0/0 on a set of measure zero), not a failure.
BOUNDARY_ULPS = 4
#: BOUNDARY_ULPS as a distance: 4 * 2^-23, about 4.8e-7 (coordinates, radii and z of unit vectors alike).
BOUNDARY_TOLERANCE = BOUNDARY_ULPS * 2.0 ** -23


def sidak_level(alpha: float, n_tests: int) -> float:
    """Per-test significance that keeps the family-wise false-alarm rate at `alpha` over `n_tests`."""
    return 1.0 - (1.0 - alpha) ** (1.0 / max(n_tests, 1))

#: Independent batches each engine renders for an image comparison.
IMAGE_BATCHES = 8
#: Side of the square tiles of the middle test scale, in pixels.
TILE_SIZE = 8
#: Differences below this fraction of a value are float32 rounding, not bias (a floor on the standard error).
ROUNDING_TOLERANCE = 1e-5
#: A pixel variance below this fraction of what the better-sampled side predicts for it is taken as a
#: contribution all its batches missed (harness.statistics.welch.sample_floor).
MISSED_CONTRIBUTION = 0.1
#: Side of the neighbourhood (pixels or tiles) whose variances are the prior of an element's moderated variance.
MODERATION_WINDOW = 3
#: Power figures of image comparisons: the bias detected in this fraction of runs.
IMAGE_POWER_TARGET = 0.5
#: Two batches are dependent (harness.statistics.independence) when their residual correlation is at least this
#: large (independent batches: -1 / (K - 1), identical: 1) and significant at DEPENDENCE_LEVEL.
DEPENDENCE_CORRELATION = 0.3
DEPENDENCE_LEVEL = 1e-3
#: Side in pixels of the blocks whose sums are the clusters of that test.
DEPENDENCE_CLUSTER = 4
#: Side in pixels of the neighbourhood whose largest reference variance an element's test variance is held
#: against (harness.statistics.excess_spread).
SPREAD_WINDOW = 5
#: A batch whose image mean stands apart from the others' (harness.statistics.outlier_batch) at this level fails
#: the comparison: fixed, as DEPENDENCE_LEVEL is, far below every comparison's share of the run's level.
OUTLIER_LEVEL = 1e-6
#: A comparison that cannot find a relative bias of the image mean this large half of the time (at its noise
#: and level) is INCONCLUSIVE, never a PASS: it says the samples per pixel that would decide it.
INCONCLUSIVE_BIAS = 0.05
#: The strategy check (harness.comparison.strategies) compares blocks of at least this many pixels a side, not
#: pixels: one strategy's samples can be so heavy-tailed at the suite's budget (BSDF sampling of a small light:
#: most of a pixel's batches never hit it) that Welch's t on K batch values is far too liberal per pixel.
STRATEGY_BLOCK = 8
#: ... and at most this many blocks a side: more blocks test each at a more extreme level, deeper in the tail
#: of the heavy-tailed strategy (8-pixel blocks of a 128 x 128 Cornell box called a correct renderer's BSDF
#: sampling different in half of 200 null triples; 16-pixel blocks, 8 a side, did not).
STRATEGY_GRID = 8
#: Side, in blocks, of the strategy check's middle scale (32 x 32 pixels).
STRATEGY_TILE = 4
