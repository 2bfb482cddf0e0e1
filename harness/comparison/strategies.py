"""The strategies agree: direct lighting by emitter sampling alone ("ems"), by BSDF sampling alone ("mats") and by
both with multiple importance sampling ("mis") estimates one image, so one engine's three renders of a scene are
compared with each other by the mean test (`compare_summaries`), pairwise, and the strategy that differs from
the other two is named. No reference is needed: a wrong light pdf biases "ems" alone, a wrong BSDF pdf "mats"
alone, MIS weights that do not sum to one "mis" alone.

The renders are compared in square blocks of pixels (each block's mean per batch; the scales are then blocks,
tiles of STRATEGY_TILE x STRATEGY_TILE blocks, and the image), STRATEGY_BLOCK pixels a side or more, so that
the image holds at most STRATEGY_GRID blocks a side: BSDF sampling of a small light is so heavy-tailed at the
suite's budget that most of a pixel's K batches never hit it, and Welch's t on such K values rejected every one
of 200 null triples of Mitsuba's Cornell box at the pixel scale; more, smaller blocks are each tested at a more
extreme level, deeper in that tail. A strategy's bias (a pdf, a weight) spans many blocks.

The family-wise level `alpha` is split over the three comparisons by Sidak (each at 1 - (1 - alpha)^(1/3));
within a comparison it is split over its scales as everywhere else. A correct renderer is then called anything
but "agree" at most `alpha` of the time: the three comparisons share renders, and Sidak's bound holds for such
positively dependent two-sided tests of normal statistics (Bonferroni's, a hair larger, always); the
calibration (docs/statistics.md) measures it. The strategies draw different
estimators, so their relative noise is reported, never judged, and all three are rendered at one budget (the
sample floor would otherwise predict one strategy's noise from another's).

Verdicts:
- AGREE: no comparison rejects and each could have found a bias of the image mean of INCONCLUSIVE_BIAS;
- DIFFERS: the two comparisons of one strategy reject and the third passes: that strategy is named (`odd`);
- INCONCLUSIVE: a pattern that names no single strategy (one comparison rejects alone: a bias that only the
  quieter pair resolves; all three reject: more than one strategy is wrong), or no rejection where some pair
  could not have found the bias it must resolve. `disagree` tells the first kind, which is no pass, from the
  second. Where all three reject, the two strategies nearest each other are `suspects` when they share a part
  (ems and mis the light's sampling, mats and mis the BSDF's): a light pdf left in area measure biases MIS too,
  which weighs a small light's samples by nearly 1, so "ems" alone is never the odd one there.

Public API::

    check = compare_strategies({"ems": a, "mats": b, "mis": c}, alpha=0.01, spp=32)   # (K, H, W, 3) or renders
    check.verdict, check.odd, check.suspects, check.reason, check.pairs, check.to_json()
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from itertools import combinations
from typing import Protocol, Union

import numpy as np

from harness.comparison.compare import compare_summaries
from harness.comparison.outcome import Comparison
from harness.comparison.summary import Summary, summarize, tile_means
from harness.statistics.independence import batch_dependence
from harness.statistics.constants import SIGNIFICANCE, STRATEGY_BLOCK, STRATEGY_GRID, STRATEGY_TILE, sidak_level

#: The three estimators of direct lighting, in the order their comparisons are made and reported.
STRATEGIES = ("ems", "mats", "mis")
#: What a wrong strategy most likely has wrong, for the reason's last words.
SUSPECTS = {"ems": "the light's sampling or its pdf (a pdf left in area measure?)",
            "mats": "the BSDF's sampling or its pdf",
            "mis": "the MIS weights (the two strategies agree without them: weights that do not sum to one?)"}

#: Two strategies that both differ from the third, and less from each other, share their defect: what they share.
SHARED = {frozenset(("ems", "mis")): "the light's sampling or its pdf, which ems and mis share (MIS weighs its light "
                                     "samples the more, the smaller the light)",
          frozenset(("mats", "mis")): "the BSDF's sampling or its pdf, which mats and mis share"}
#: The nearest pair is named only where each other pair is at least this many times as far apart.
NEAREST_MARGIN = 2.0


class Batches(Protocol):
    """A render with its K batches at hand (harness.engines.base.RenderResult)."""

    batches: np.ndarray | None


Render = Union[np.ndarray, Batches]


@dataclass(frozen=True, kw_only=True)
class StrategyPair:
    """One of the three comparisons: `first` as the test side, `second` as the reference side."""

    first: str
    second: str
    comparison: Comparison

    @property
    def rejects(self) -> bool:
        return not self.comparison.passed

    @property
    def names(self) -> tuple[str, str]:
        return self.first, self.second

    @property
    def summary(self) -> str:
        """One line: "ems vs mats: PASS", "ems vs mis: FAIL (image, tile scale(s) reject)"."""
        c = self.comparison
        why = c.reason if self.rejects else c.inconclusive
        return f"{self.first} vs {self.second}: {c.verdict}" + (f" ({why})" if why else "")

    def to_json(self) -> dict:
        return {"first": self.first, "second": self.second, "rejects": self.rejects, "summary": self.summary,
                "comparison": self.comparison.to_json()}


@dataclass(frozen=True, kw_only=True)
class StrategyCheck:
    """The three comparisons and what their pattern says."""

    pairs: tuple[StrategyPair, ...]
    #: The family-wise false-alarm rate of the three comparisons together, and each one's Sidak share.
    level: float
    pair_level: float
    #: "AGREE", "DIFFERS" or "INCONCLUSIVE".
    verdict: str
    #: The strategy that differs from the other two (DIFFERS), else None.
    odd: str | None
    #: Why, in one line.
    reason: str
    #: The strategies a disagreement points at: the odd one (DIFFERS), or where every pair disagrees the two
    #: that differ less from each other than from the third, when they share a part (SHARED); else none.
    suspects: tuple[str, ...] = ()

    @property
    def disagree(self) -> bool:
        """Some comparison rejects: the strategies do not all estimate one image (named or not)."""
        return any(p.rejects for p in self.pairs)

    def pair(self, a: str, b: str) -> StrategyPair:
        """The comparison of strategies `a` and `b`, in either order."""
        return next(p for p in self.pairs if set(p.names) == {a, b})

    def to_json(self) -> dict:
        return {"verdict": self.verdict, "odd": self.odd, "suspects": list(self.suspects), "reason": self.reason,
                "disagree": self.disagree,
                "level": self.level, "pair_level": self.pair_level, "pairs": [p.to_json() for p in self.pairs]}


def _batches(name: str, render: Render) -> np.ndarray:
    """A render's (K, H, W, 3) batches in float64."""
    batches = render if isinstance(render, np.ndarray) else getattr(render, "batches", None)
    if batches is None:
        raise ValueError(f"strategy {name!r}: its batches are not at hand (a render without batches, or None)")
    b = np.asarray(batches, np.float64)
    if b.ndim != 4 or b.shape[-1] != 3:
        raise ValueError(f"strategy {name!r}: expected (K, H, W, 3) batches, got shape {b.shape}")
    return b


def block_side(height: int, width: int) -> int:
    """The side of the blocks compared: STRATEGY_BLOCK pixels, or more where the image would hold more than
    STRATEGY_GRID blocks a side (16 at 128 x 128)."""
    return max(STRATEGY_BLOCK, -(-max(height, width) // STRATEGY_GRID))


def _block_summary(batches: np.ndarray, block: int, tile: int) -> Summary:
    """The Summary of the batches' `block` x `block` means, keeping what blocks would hide: each block's smallest
    pixel value (a negative pixel among positive ones), and whether the batches are independent, judged on
    their pixels."""
    with np.errstate(invalid="ignore", over="ignore"):  # NaN and Inf propagate; the finite check reports them
        summary = summarize(tile_means(batches, block), tile)
        smallest = batches.min(axis=0)
    h, w, c = smallest.shape
    bh, bw = -(-h // block), -(-w // block)
    padded = np.full((bh * block, bw * block, c), np.inf)
    padded[:h, :w] = smallest
    minimum = padded.reshape(bh, block, bw, block, c).min(axis=(1, 3))
    return replace(summary, minimum=minimum, dependence=batch_dependence(batches))


def _spp(renders: Mapping[str, Render], spp: int | None) -> int | None:
    """The one budget of the three renders: `spp` if given, else the renders' own (`spp` attributes) when they
    all say one count. Different counts are refused: the sample floor would predict one strategy's noise from
    another's, which draws another estimator."""
    counts = {getattr(r, "spp") for r in renders.values() if isinstance(getattr(r, "spp", None), int)}
    if len(counts) > 1:
        raise ValueError(f"the strategies were rendered at different samples per pixel ({sorted(counts)}): "
                         "compare them at one budget")
    if spp is not None and counts and counts != {spp}:
        raise ValueError(f"spp={spp} given, but the renders hold {counts.pop()} samples per pixel")
    return spp if spp is not None else (counts.pop() if counts else None)


def compare_strategies(renders: Mapping[str, Render], *, alpha: float = SIGNIFICANCE, spp: int | None = None,
                       block: int | None = None, tile: int = STRATEGY_TILE, power: bool = True,
                       metrics: bool = False) -> StrategyCheck:
    """Compare the renders of STRATEGIES ("ems", "mats", "mis": each (K, H, W, 3) batches, or a render whose
    `batches` are at hand, harness.engines.base.RenderResult) pairwise at the family-wise level `alpha`, in
    blocks of `block` pixels a side (None: `block_side`) and tiles of `tile` blocks, and name the one that
    differs.

    `spp`: the samples per pixel of each batch, one count for all three (None: the renders' own, or unknown);
    with it each comparison reports the strategies' relative noise where its blocks make tiles enough (never a
    failure: they are other estimators).
    `power` False skips the detectable biases (null and planted runs that only count verdicts): a pass is then
    AGREE without asking whether it could have found a bias. `metrics` adds the error metrics to each comparison.
    """
    missing = [s for s in STRATEGIES if s not in renders]
    extra = sorted(set(renders) - set(STRATEGIES))
    if missing or extra:
        raise ValueError(f"expected renders named {', '.join(STRATEGIES)}; "
                         + "; ".join(filter(None, [missing and f"missing {', '.join(missing)}",
                                                   extra and f"unknown {', '.join(extra)}"])))
    budget = _spp(renders, spp)
    batches = {name: _batches(name, renders[name]) for name in STRATEGIES}
    if len({b.shape[1:] for b in batches.values()}) > 1:
        raise ValueError("the strategies' images differ in size: "
                         + ", ".join(f"{n} {b.shape[2]}x{b.shape[1]}" for n, b in batches.items()))
    h, w = next(iter(batches.values())).shape[1:3]
    block = block_side(h, w) if block is None else block
    summaries = {name: _block_summary(b, block, tile) for name, b in batches.items()}
    samples = None if budget is None else budget * block * block  # per block and batch (fewer at the edges: alike)
    pair_level = sidak_level(alpha, 3)
    pairs = tuple(StrategyPair(first=a, second=b, comparison=compare_summaries(
        summaries[a], summaries[b], pair_level, samples=(samples, samples), metrics=metrics, power=power,
        tile_power=False)) for a, b in combinations(STRATEGIES, 2))
    verdict, odd, reason = read_pattern(pairs, alpha, pair_level)
    suspects: tuple[str, ...] = (odd,) if odd else ()
    if all(p.rejects for p in pairs):
        suspects, why = nearest_pair({name: s.image.mean for name, s in summaries.items()})
        reason += why
    return StrategyCheck(pairs=pairs, level=alpha, pair_level=pair_level, verdict=verdict, odd=odd, reason=reason,
                         suspects=suspects)


def nearest_pair(means: Mapping[str, np.ndarray]) -> tuple[tuple[str, ...], str]:
    """Where every pair disagrees (two strategies or more are wrong): the two whose image means (`means`, by
    strategy) are nearest each other, with what they share, when each other pair is NEAREST_MARGIN times as
    far apart and they share a part (SHARED): both are suspects, a defect of that part. ((), "") otherwise.
    A reading of the figures, not a test: the verdict stays INCONCLUSIVE."""
    def apart(a: str, b: str) -> float:
        ma, mb = np.asarray(means[a], np.float64), np.asarray(means[b], np.float64)
        with np.errstate(invalid="ignore", divide="ignore"):
            return float(np.nanmean(np.abs(ma - mb) / (0.5 * (np.abs(ma) + np.abs(mb)))))
    distances = sorted((apart(a, b), (a, b)) for a, b in combinations(STRATEGIES, 2))
    (near, pair), rest = distances[0], distances[1:]
    shared = SHARED.get(frozenset(pair))
    if shared is None or not np.isfinite(near) or any(not d >= NEAREST_MARGIN * near for d, _ in rest):
        return (), ""
    (third,) = set(STRATEGIES) - set(pair)
    return pair, (f"; {pair[0]} and {pair[1]} are nearest each other (image means {near:.2%} apart, {third} "
                  f"{min(d for d, _ in rest):.0%} or more from both): suspect {shared}")


def read_pattern(pairs: tuple[StrategyPair, ...], alpha: float, pair_level: float) -> tuple[str, str | None, str]:
    """(verdict, odd, reason) of the three comparisons' outcomes (see the module's docstring)."""
    rejected = [p for p in pairs if p.rejects]
    levels = f"3 comparisons at {pair_level:.3g} each, {alpha:g} together"
    if not rejected:
        weak = [p for p in pairs if p.comparison.inconclusive]
        if weak:
            return ("INCONCLUSIVE", None, f"no comparison rejects, but {'; '.join(p.summary for p in weak)} "
                    f"({levels})")
        return "AGREE", None, f"{', '.join(STRATEGIES[:-1])} and {STRATEGIES[-1]} agree ({levels})"
    if len(rejected) == 2:
        (odd,) = set(rejected[0].names) & set(rejected[1].names)
        kept = next(p for p in pairs if not p.rejects)
        return ("DIFFERS", odd, f"{odd} differs from {kept.first} and {kept.second}, which agree: "
                f"{'; '.join(p.summary for p in rejected)} ({levels}); suspect {SUSPECTS.get(odd, odd)}")
    if len(rejected) == 1:
        p = rejected[0]
        (third,) = set(STRATEGIES) - set(p.names)
        return ("INCONCLUSIVE", None, f"{p.first} and {p.second} disagree while {third} agrees with both: no "
                f"single strategy is named (a bias only the quieter pair resolves?); {p.summary} ({levels})")
    return ("INCONCLUSIVE", None, f"every pair disagrees: more than one strategy differs; "
            f"{'; '.join(p.summary for p in rejected)} ({levels})")
