"""Why the pixel scale keeps each pixel's own variance as a floor: its false-alarm rate on null pairs under
three rules for a pixel's variance, beside its nominal level (its Sidak share of the comparison's).

- harness: moderated towards the 3x3 neighbours' variances, never below the pixel's own (the rule in use);
- own: the pixel's own K-batch variance, K - 1 degrees of freedom (exact for Gaussian batches);
- moderated: moderated alone, which may fall below the pixel's own.

    .venv/bin/python -m tools.pixel_variance_rules                # synthetic, then every nulls-*.npz
    .venv/bin/python -m tools.pixel_variance_rules PATH.npz ...   # pairs from tools/null_renders.py

A rule is acceptable only if it is not liberal on any set: the worse error is a false FAIL. The last
column is how often a pixel's own-variance p-value falls below 1e-4, over 1e-4: above 1 where the
batches' skew makes Student's t tail too light.
"""
from __future__ import annotations

import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

import harness.comparison.compare as compare
from harness.images.suite import TESTED_SPP
from harness.statistics.constants import sidak_level
from harness.statistics.welch import moderate, sample_floor, welch_p_values
from tools.image_calibration import NULLS, SYNTHETIC_SAMPLES, render_pairs, synthetic_pairs

RULES = {"harness": compare._at_least_own, "own": lambda stats: stats, "moderated": moderate}
LEVELS = (0.3, 0.05)
#: The per-pixel level of the own-variance tail ratio: about a pixel family's per-test level.
TAIL = 1e-4


@contextmanager
def pixel_rule(rule):
    """compare_summaries with `rule` for the pixel variances."""
    kept = compare._at_least_own
    compare._at_least_own = rule
    try:
        yield
    finally:
        compare._at_least_own = kept


def pixel_rates(pairs, samples) -> dict[str, list[float]]:
    """Per rule, the pixel scale's rejection rate at each comparison level of LEVELS."""
    summaries = [(compare.summarize(a), compare.summarize(b)) for a, b in pairs]
    out = {}
    for name, rule in RULES.items():
        with pixel_rule(rule):
            out[name] = [float(np.mean([not compare.compare_summaries(a, b, level, samples=samples).scales[0].passed
                                        for a, b in summaries])) for level in LEVELS]
    return out


def own_tail(pairs, samples, p: float = TAIL) -> float:
    """How much more often than `p` a live pixel's own-variance Welch p-value falls below `p` (1 for t-tails
    that fit the batches)."""
    below = live = 0
    for a, b in pairs:
        a, b = compare.summarize(a).pixel, compare.summarize(b).pixel
        test, ref = sample_floor(a, b, *samples)
        values = welch_p_values(test, ref)[0][~compare._noiseless(a, b)]
        below, live = below + int(np.count_nonzero(values < p)), live + values.size
    return below / max(live, 1) / p


def main(argv: list[str]) -> None:
    nominal = ", ".join(f"{sidak_level(level, 3):.3f}" for level in LEVELS)
    print(f"pixel-scale false-alarm rate at comparison levels {LEVELS} (pixel nominal {nominal})")
    draw = synthetic_pairs(1, size=24)
    sets = [("synthetic Gaussian", [draw() for _ in range(400)], SYNTHETIC_SAMPLES)]
    for path in [Path(a) for a in argv] if argv else sorted(NULLS.glob("nulls-*.npz")):
        for case in sorted({key.rsplit(":", 2)[0] for key in np.load(path).files}):
            spp = TESTED_SPP[case.split(":")[1]]
            sets.append((case, render_pairs(path, case), (spp, spp)))
    for name, pairs, samples in sets:
        cells = "  ".join(f"{rule} {' / '.join(f'{r:.3f}' for r in rates)}"
                          for rule, rates in pixel_rates(pairs, samples).items())
        print(f"{name:24s} {len(pairs):4d} pairs  {cells}  own tail at {TAIL:g}: "
              f"{own_tail(pairs, samples):.2f}x", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
