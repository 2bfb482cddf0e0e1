"""What a check found at individual samples, as failures and warnings grouped by kind, most serious first.

Each sample of a warp, with the pdf at it, is sorted into at most one kind:

* FAIL: a NaN/Inf sample; a sample outside the domain; a NaN/Inf or negative pdf
  at a sample; a pdf of 0 at a sample strictly inside the support;
* WARN: a pdf of 0 at a sample on the domain's boundary (within BOUNDARY_TOLERANCE
  of it, see Domain.on_boundary), a set of measure zero where the caller's f/pdf
  is 0/0 and must be guarded;
* WARN: any failure at an input with a coordinate u = 1, which lies outside the
  [0, 1) a sampler is fed.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from harness.warps.domains import Domain
from harness.statistics.constants import BOUNDARY_TOLERANCE

#: Inputs quoted per finding (the count says how many there are in all).
MAX_EXAMPLES = 3


@dataclass(frozen=True)
class Kind:
    """One kind of finding: its key in JSON, its severity, its wording and the advice it implies."""

    key: str
    severity: str
    title: str
    advice: str = ""


#: Every kind, most serious first; a sample's code is its kind's index here plus one (0: nothing found).
KINDS = (
    Kind("nan_sample", "FAIL", "NaN/Inf sample", "a NaN sample poisons every estimate it reaches"),
    Kind("outside", "FAIL", "sample outside the domain"),
    Kind("nan_pdf", "FAIL", "NaN/Inf pdf at a sample"),
    Kind("negative_pdf", "FAIL", "negative pdf at a sample"),
    Kind("zero_pdf_inside", "FAIL", "pdf 0 at a sample inside the support",
         "the sampler draws points its pdf calls impossible"),
    Kind("pdf_off_domain", "FAIL", "pdf > 0 off the domain", "the pdf must return 0 outside the domain"),
    Kind("zero_pdf_boundary", "WARN", "pdf 0 at a sample on the boundary", "f/pdf at this sample is 0/0: guard it"),
    Kind("at_u_one", "WARN", "failure at u = 1", "u = 1 is outside [0, 1): fine for samplers fed [0,1)"),
)
_CODE = {k.key: i + 1 for i, k in enumerate(KINDS)}


@dataclass
class Finding:
    """How many inputs (or samples) show one kind of problem, with the first few of them quoted."""

    kind: Kind
    count: int
    examples: list[str] = field(default_factory=list)

    @property
    def severity(self) -> str:
        return self.kind.severity

    def text(self) -> str:
        """One line: severity, kind, count, the quoted inputs and the advice."""
        more = f" (+{self.count - len(self.examples)} more)" if self.count > len(self.examples) else ""
        advice = f" — {self.kind.advice}" if self.kind.advice else ""
        return f"{self.severity} {self.kind.title} ×{self.count}: {'; '.join(self.examples)}{more}{advice}"

    def to_json(self) -> dict[str, Any]:
        return {"severity": self.severity, "kind": self.kind.key, "count": self.count,
                "examples": self.examples, "advice": self.kind.advice, "text": self.text()}


def classify(domain: Domain, points: np.ndarray, values: np.ndarray, at_one: np.ndarray | None = None,
             tol: float = BOUNDARY_TOLERANCE) -> tuple[np.ndarray, np.ndarray]:
    """Per sample, the code of its kind (0: fine), and the code it had before the u = 1 rule.

    points: (N, dim) samples; values: (N,) pdf at them; at_one: (N,) whether the input that produced
    each sample had a coordinate equal to 1 (None: unknown, no such inputs); tol: boundary distance.
    """
    finite = np.all(np.isfinite(points), axis=1)
    safe = np.where(finite[:, None], points, 0.0)
    inside = finite & domain.contains(safe)
    zero = inside & (values == 0)
    edge = zero & domain.on_boundary(safe, tol)
    codes = np.zeros(len(points), dtype=np.int8)
    # Assigned from the least to the most serious, so the most serious kind of a sample wins.
    for key, mask in (("zero_pdf_boundary", edge), ("zero_pdf_inside", zero & ~edge),
                      ("negative_pdf", inside & (values < 0)), ("nan_pdf", inside & ~np.isfinite(values)),
                      ("outside", finite & ~inside), ("nan_sample", ~finite)):
        codes[mask] = _CODE[key]
    underlying = codes.copy()
    if at_one is not None:
        failing = np.isin(codes, [_CODE[k.key] for k in KINDS if k.severity == "FAIL"])
        codes[failing & at_one] = _CODE["at_u_one"]
    return codes, underlying


def count(codes: np.ndarray, key: str) -> int:
    """How many samples have the kind `key`."""
    return int(np.count_nonzero(codes == _CODE[key]))


def _vector(x: np.ndarray) -> str:
    return "(" + ", ".join(f"{float(c):.6g}" for c in x) + ")"


def _input(u: np.ndarray) -> str:
    return "(" + ", ".join(repr(float(c)) for c in u) + ")"


def describe(codes: np.ndarray, underlying: np.ndarray, points: np.ndarray, values: np.ndarray,
             u: np.ndarray | None = None, seen: np.ndarray | None = None, label: str = "") -> list[Finding]:
    """The findings of one classified batch, most serious first, each quoting its first inputs.

    u: the (N, 2) inputs behind the samples (None: random ones, not quoted); seen: the inputs as the
    sampler received them (e.g. rounded to float32), quoted where they differ; label: e.g. "alpha=0.3".
    """
    out = []
    present = np.flatnonzero(np.bincount(codes, minlength=1))
    for code in present[present > 0]:
        kind = KINDS[code - 1]
        rows = np.flatnonzero(codes == code)
        examples = []
        for k in rows[:MAX_EXAMPLES]:
            text = f"[{label}] " if label else ""
            if u is not None:
                text += f"u={_input(u[k])}"
                if seen is not None and np.any(seen[k] != u[k]):
                    text += f" (received as {_input(seen[k])})"
                text += " → "
            text += f"sample {_vector(points[k])}"
            if kind.key != "nan_sample" and underlying[k] != _CODE["nan_sample"]:
                text += f", pdf {float(values[k]):.6g}"
            if kind.key == "at_u_one":
                text += f" [{KINDS[underlying[k] - 1].title}]"
            examples.append(text)
        out.append(Finding(kind, len(rows), examples))
    return out


def off_domain(probes: np.ndarray, values: np.ndarray) -> list[Finding]:
    """The finding of a pdf that is not 0 at points outside the domain (none if it is 0 at all of them)."""
    rows = np.flatnonzero(values != 0)
    if not len(rows):
        return []
    examples = [f"point {_vector(probes[k])}, pdf {float(values[k]):.6g}" for k in rows[:MAX_EXAMPLES]]
    return [Finding(KINDS[_CODE["pdf_off_domain"] - 1], len(rows), examples)]


def merge(groups: list[list[Finding]]) -> list[Finding]:
    """Findings of several batches (e.g. one per parameter value) as one list: kinds summed, most serious first."""
    merged: dict[str, Finding] = {}
    for group in groups:
        for f in group:
            if f.kind.key in merged:
                m = merged[f.kind.key]
                m.count += f.count
                m.examples = (m.examples + f.examples)[:MAX_EXAMPLES]
            else:
                merged[f.kind.key] = Finding(f.kind, f.count, list(f.examples))
    return sorted(merged.values(), key=lambda f: _CODE[f.kind.key])


def summarize(findings: list[Finding], ok_text: str) -> str:
    """A short line: the most serious finding with its first input, then the other kinds with their counts."""
    if not findings:
        return ok_text
    first, rest = findings[0], findings[1:]
    head = f"{'' if first.severity == 'FAIL' else 'warn: '}{first.kind.title} ×{first.count}: {first.examples[0]}"
    tail = [f"{'' if f.severity == 'FAIL' else 'warn: '}{f.kind.title} ×{f.count}" for f in rest]
    return "; ".join(([] if first.severity == "FAIL" else [ok_text]) + [head, *tail])
