"""The terminal table of a bench run: efficiency ratios per case and each engine's convergence slope."""
from __future__ import annotations

from rich.table import Table

from harness.bench.run import SAME_SAMPLER
from harness.bench.throughput import REFERENCE, TESTED


def _unmeasured(comparison: dict) -> str | None:
    """Why a comparison has no ratio (an engine without that curve, or errors below the reference's noise)."""
    if comparison["missing"]:
        return f"no {' or '.join(comparison['missing'])} curve"
    return "below ref. noise" if comparison["ratio"] != comparison["ratio"] else None


def bench_table(benches, engines) -> Table:
    """One row per case: the tested engine's efficiency over the reference's with the same sampler, best against
    best, each engine's slope."""
    table = Table(title="Speed against error", header_style="bold")
    tested = engines[0].name if engines else "tested"
    compared = benches[0].reference if benches else "reference"
    for col in ("scene", "integrator", f"efficiency {tested}/{compared}, same sampler", "best against best",
                *[f"slope {e.label}" for e in engines]):
        table.add_column(col)
    for bch in benches:
        same, best = bch.comparison(SAME_SAMPLER), bch.comparison(None)
        ratio = same["ratio"]
        shown = _unmeasured(same) or f"[{'green' if ratio >= 1 else 'red'}]{ratio:.2f}[/]"
        best_text = _unmeasured(best) or f"{best['ratio']:.2f} ({best['tested']} / {best['reference']})"
        table.add_row(bch.case.scene, bch.case.integrator, shown, best_text,
                      *[f"{c.fit('spp')[0]:.2f}" for c in bch.curves.values()])
    return table


def bench_lines(payload: dict) -> list[str]:
    """The throughput, sampler-slope and seed-settings figures of a bench run, a line each."""
    lines = []
    for t in payload["throughput"] or []:
        lines.append(f"throughput {t['scene']}:{t['integrator']} {t['resolution']}² {t['spp']} spp "
                     f"({t['sampler']}): {t['engines'][TESTED]} {t['median_seconds'][TESTED]:.3f} s, "
                     f"{t['engines'][REFERENCE]} {t['median_seconds'][REFERENCE]:.3f} s, reference/tested "
                     f"{t['reference_over_tested']:.2f}"
                     + (f", in its worker {t['reference_over_tested_worker']:.2f}"
                        if "reference_over_tested_worker" in t else ""))
    for integrator, by_sampler in (payload["sampler_slopes"] or {}).get("slopes", {}).items():
        lines.append(f"MSE slope on cornell {integrator}: " + ", ".join(f"{k} {v:.2f}" for k, v in by_sampler.items()))
    for name, v in (payload["seed_comparison"] or {}).items():
        reference = f", reference {v['reference_seconds']:.2f} s" if "reference_seconds" in v else ""
        lines.append(f"seed settings, {name}: tested {v['seconds']:.2f} s{reference} (seed document "
                     f"{v['seed_seconds']} s)")
    return lines
