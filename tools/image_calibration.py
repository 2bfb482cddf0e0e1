"""How often the image comparison rejects a correct renderer, and how often it finds `detectable_bias`.

Measures, through `compare_summaries`, on pairs of null renders (two independent runs of one engine):
the rejection rate per scale and of the whole comparison at a nominal `alpha`, with its Clopper-Pearson
interval, and the rate at which a bias equal to the reported `detectable_bias` (the test scaled by
1 + b) is found by the image scale. Pairs are synthetic (heteroscedastic Gaussian pixels) or real
renders (an .npz of K1 and K2 batches per pair).

    .venv/bin/python -m tools.image_calibration              # synthetic, then every NULLS/nulls-*.npz
    .venv/bin/python -m tools.image_calibration PATH.npz ... # renders: keys "scene:integrator:pair:a|b"

The render pairs are made by tools/null_renders.py.
"""
from __future__ import annotations

import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import stats as sps

from harness.comparison.compare import SCALES, compare_summaries
from harness.comparison.summary import summarize
from harness.images.suite import TESTED_SPP
from harness.statistics.constants import TILE_SIZE

NULLS = Path(__file__).resolve().parent.parent / "results" / "calibration"
Pair = tuple[np.ndarray, np.ndarray]
Samples = tuple[int, int]
#: The synthetic reference's batches have a sixteenth of the test's variance: sixteen times the samples.
SYNTHETIC_SAMPLES = (1, 16)


@dataclass
class Rates:
    """Rejections of `runs` null pairs at nominal `alpha`, per scale and for the whole comparison."""

    alpha: float
    runs: int
    per_scale: dict[str, int]
    whole: int

    def interval(self, count: int, confidence: float = 0.95) -> tuple[float, float]:
        """Clopper-Pearson interval of a rejection rate."""
        lo = sps.beta.ppf((1 - confidence) / 2, count, self.runs - count + 1) if count else 0.0
        hi = sps.beta.isf((1 - confidence) / 2, count + 1, self.runs - count) if count < self.runs else 1.0
        return float(lo), float(hi)

    def rate(self, scale: str | None = None) -> float:
        return (self.whole if scale is None else self.per_scale[scale]) / self.runs

    def __str__(self) -> str:
        lo, hi = self.interval(self.whole)
        scales = " ".join(f"{s} {self.rate(s):.3f}" for s in SCALES)
        return f"alpha {self.alpha}: whole {self.rate():.3f} [{lo:.3f}, {hi:.3f}] of {self.runs}; {scales}"


def null_rates(pairs: Iterable[Pair], alpha: float, samples: Samples = SYNTHETIC_SAMPLES) -> Rates:
    """Rejection rates of `compare_summaries` at `alpha` over null (test, reference) batch pairs whose
    batches hold `samples` samples per pixel."""
    per_scale, whole, runs = dict.fromkeys(SCALES, 0), 0, 0
    for test, reference in pairs:
        result = compare_summaries(summarize(test), summarize(reference), alpha, samples=samples, metrics=False,
                                   power=False)
        for s in result.scales:
            per_scale[s.scale] += not s.passed
        whole += not result.passed
        runs += 1
    return Rates(alpha, runs, per_scale, whole)


def detection_rate(pairs: Iterable[Pair], fresh: Callable[[], Pair],
                   samples: Samples = SYNTHETIC_SAMPLES) -> tuple[float, int, float]:
    """(fraction found by the image scale, runs, median bias): each pair's `detectable_bias` is planted
    (the test scaled by 1 + b) into a fresh independent pair from `fresh`."""
    found, runs, biases = 0, 0, []
    for test, reference in pairs:
        bias = compare_summaries(summarize(test), summarize(reference), samples=samples, metrics=False).detectable_bias
        other_test, other_reference = fresh()
        result = compare_summaries(summarize(other_test * (1 + bias)), summarize(other_reference), samples=samples,
                                   metrics=False, power=False)
        found += not result.scales[2].passed
        runs += 1
        biases.append(bias)
    return found / runs, runs, float(np.median(biases))


def tile_detection_rate(pairs: Iterable[Pair], fresh: Callable[[], Pair], seed: int = 0,
                        samples: Samples = SYNTHETIC_SAMPLES) -> tuple[float, int, float]:
    """(fraction found by the tile scale, runs, median bias): each pair's `detectable_tile_bias` is planted
    into one tile, drawn at random, of a fresh independent pair (that tile's test values scaled by 1 + b)."""
    rng = np.random.default_rng(seed)
    found, runs, biases = 0, 0, []
    for test, reference in pairs:
        bias = compare_summaries(summarize(test), summarize(reference), samples=samples,
                                 metrics=False).detectable_tile_bias
        other_test, other_reference = fresh()
        h, w = other_test.shape[1:3]
        y, x = TILE_SIZE * rng.integers(h // TILE_SIZE), TILE_SIZE * rng.integers(w // TILE_SIZE)
        planted = other_test.copy()
        planted[:, y:y + TILE_SIZE, x:x + TILE_SIZE] *= 1 + bias
        result = compare_summaries(summarize(planted), summarize(other_reference), samples=samples, metrics=False,
                                   power=False)
        found += not result.scales[1].passed
        runs += 1
        biases.append(bias)
    return found / runs, runs, float(np.median(biases))


def synthetic_pairs(seed: int, size: int = 32, k: tuple[int, int] = (8, 16)) -> Callable[[], Pair]:
    """A source of null pairs: Gaussian pixels whose mean and standard deviation vary smoothly over the
    image and by a random factor per pixel and channel (heteroscedastic); the reference side has
    `k[1]` batches with a quarter of the noise (a bigger budget per batch)."""
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:size, 0:size] / size
    mean = (5.0 + np.sin(6 * xx) * np.cos(4 * yy))[..., None] * np.array([1.0, 0.8, 0.6])
    sd = 0.1 * (0.2 + xx * yy)[..., None] * np.minimum(rng.lognormal(0.0, 0.5, (size, size, 3)), 3.0)

    def draw() -> Pair:
        return (mean + sd * rng.standard_normal((k[0], size, size, 3)),
                mean + 0.25 * sd * rng.standard_normal((k[1], size, size, 3)))

    return draw


def render_pairs(path: Path, case: str | None = None) -> list[Pair]:
    """Null pairs stored in an .npz (keys "scene:integrator:pair:a" and ":b"), of one case or all."""
    data = np.load(path)
    names = sorted({key.rsplit(":", 1)[0] for key in data.files})
    return [(data[f"{n}:a"].astype(np.float64), data[f"{n}:b"].astype(np.float64)) for n in names
            if case is None or n.startswith(case + ":")]


def main(argv: list[str]) -> None:
    draw = synthetic_pairs(0)
    for alpha, runs in ((0.3, 400), (0.05, 400), (0.01, 400)):
        print("synthetic", null_rates((draw() for _ in range(runs)), alpha))
    rate, runs, bias = detection_rate((draw() for _ in range(200)), draw)
    print(f"synthetic detectable_bias (median {bias:.2e}) found {rate:.3f} of {runs}")
    rate, runs, bias = tile_detection_rate((draw() for _ in range(200)), draw)
    print(f"synthetic detectable_tile_bias (median {bias:.2e}) found {rate:.3f} of {runs}")
    paths = [Path(a) for a in argv] if argv else sorted(NULLS.glob("nulls-*.npz"))
    totals: dict[float, list[Rates]] = {0.3: [], 0.05: [], 0.01: []}
    for path in paths:
        cases = sorted({key.rsplit(":", 2)[0] for key in np.load(path).files})
        for case in cases:
            mine = render_pairs(path, case)
            integrator = case.split(":")[1]
            samples = (TESTED_SPP[integrator], TESTED_SPP[integrator])  # as tools/null_renders.py makes them
            for alpha in totals:
                rates = null_rates(mine, alpha, samples)
                totals[alpha].append(rates)
                print(case, rates, flush=True)
            shifted = iter(mine[1:] + mine[:1])
            rate, runs, bias = detection_rate(mine, lambda: next(shifted), samples)
            print(f"  {case} detectable_bias (median {bias:.2e}) found {rate:.3f} of {runs}")
            shifted = iter(mine[1:] + mine[:1])
            rate, runs, bias = tile_detection_rate(mine, lambda: next(shifted), samples=samples)
            print(f"  {case} detectable_tile_bias (median {bias:.2e}) found {rate:.3f} of {runs}", flush=True)
    if len(paths) > 1:
        for alpha, parts in totals.items():
            print("all renders", Rates(alpha, sum(r.runs for r in parts),
                                       {s: sum(r.per_scale[s] for r in parts) for s in SCALES},
                                       sum(r.whole for r in parts)))

if __name__ == "__main__":
    main(sys.argv[1:])
