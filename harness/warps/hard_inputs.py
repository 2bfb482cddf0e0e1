"""The hard-inputs check: a warp on the inputs that break careless code (u = 0, denormals, 1 - ulp, 1)."""
from __future__ import annotations

import numpy as np

from harness.warps.check_result import CheckResult
from harness.warps.checks import Pdf, Sampler, as_points, as_values
from harness.warps.domains import Domain
from harness.warps.findings import classify, describe, merge, summarize


def hard_input_grid() -> np.ndarray:
    """u on a grid of values that break careless warps, in both coordinates.

    0, the smallest positive double and float, the smallest normal float, 0.5,
    one ulp below 1 in double and in float, and 1.
    """
    values = np.array([0.0, 5e-324, float(np.float32(1.4e-45)), float(np.finfo(np.float32).tiny),
                       0.5, 1.0 - 2.0 ** -53, 1.0 - 2.0 ** -24, 1.0])
    a, b = np.meshgrid(values, values, indexing="ij")
    return np.stack([a.ravel(), b.ravel()], axis=-1)


def hard_inputs_check(domain: Domain, variants: dict[str, tuple[Sampler, Pdf]]) -> CheckResult:
    """On hard inputs every sample is finite and in the domain, and its pdf finite and positive.

    `variants` maps a label (e.g. "alpha=1e-4") to a (sample, pdf) pair. Warnings, not failures: a pdf
    of 0 at a sample on the domain's boundary, and anything at an input with a coordinate u = 1 (outside
    [0, 1)). A sampler with an `input_dtype` attribute (float32 for Dr.Jit functions, see warp_adapters)
    is judged on u as it received it. `findings` come most serious first: NaN samples, naming their u.
    The figure is the number of NaN/Inf samples at inputs in [0, 1).
    """
    u = hard_input_grid()
    groups = []
    for label, (sample, pdf) in variants.items():
        points = as_points(sample(u), len(u), "sample")
        values = as_values(pdf(points), len(points), "pdf")
        seen = u.astype(getattr(sample, "input_dtype", np.float64))
        codes, underlying = classify(domain, points, values, np.any(seen == 1.0, axis=1))
        groups.append(describe(codes, underlying, points, values, u=u, seen=seen, label=label))
    findings = merge(groups)
    n = {f.kind.key: f.count for f in findings}
    nonfinite = n.get("nan_sample", 0)
    ok = not any(f.severity == "FAIL" for f in findings)
    details = {"nan_inf": nonfinite, "outside": n.get("outside", 0),
               "bad_pdf": sum(n.get(k, 0) for k in ("nan_pdf", "negative_pdf", "zero_pdf_inside")),
               "zero_pdf_on_boundary": n.get("zero_pdf_boundary", 0), "failures_at_u_one": n.get("at_u_one", 0),
               "inputs": len(u) * len(variants), "variants": list(variants)}
    return CheckResult(ok, float(nonfinite), summarize(findings, f"NaN/Inf {nonfinite}"), details=details,
                       findings=findings)
