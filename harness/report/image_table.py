"""The image verdicts as a rich table for the terminal."""
from __future__ import annotations

from rich import box
from rich.markup import escape
from rich.table import Table

from harness.comparison.finite import SIDES
from harness.images.references import CLOSED_FORM
from harness.images.result import ImageResult
from harness.images.scale_twins import SCALE_TWIN
from harness.report.idiff_text import LEGEND, idiff_short


def _bad_pixels(result: ImageResult) -> list[str]:
    """E.g. ["16 NaN/Inf, 1 negative (test)"] (pixels), one entry per damaged side of every comparison."""
    found = {}
    for c in result.comparisons.values():
        for side in SIDES:
            d = getattr(c.finite, side)
            kinds = [f"{n} {kind}" for kind, n in (("NaN/Inf", d.nonfinite), ("negative", d.negative)) if n]
            if kinds:
                found[f"{', '.join(kinds)} ({side})"] = None
    return list(found)


def _cell(result: ImageResult) -> str:
    """PASS, or FAIL with what failed: the bad pixels (NaN, Inf or negative, which make the scales
    meaningless; their locations are in the report) if any, else the failing scales."""
    if result.passed:
        return "[green]PASS[/]"
    if result.verdict == "INCONCLUSIVE":
        return "[yellow]INCONCLUSIVE[/]"
    bad_pixels = _bad_pixels(result)
    if bad_pixels:
        return f"[bold red]FAIL[/] {escape(', '.join(bad_pixels))}"
    if not all(c.independent for c in result.comparisons.values()):
        return "[bold red]FAIL[/] batches not independent"
    if not all(c.no_outlier for c in result.comparisons.values()):
        return "[bold red]FAIL[/] a batch stands apart"
    failed = sorted({s for c in result.comparisons.values() for s in c.failed_checks})
    return f"[bold red]FAIL[/] {','.join(failed)}".rstrip()


def _oracle_cell(result: ImageResult) -> str:
    """The oracle compared beside the reference engine: " (+exact)" a closed form, " (+twin)" a scale twin."""
    sources = {r.source for r in result.references.values()}
    return " (+exact)" if CLOSED_FORM in sources else " (+twin)" if SCALE_TWIN in sources else ""


def _strategies_cell(result: ImageResult) -> str:
    """The strategy check beside the verdict: "ems differs", "strategies agree", ... ("" where it did not run)."""
    check = result.strategies
    if check is None:
        return ""
    if check.verdict == "DIFFERS":
        return f" [bold red]{check.odd} differs[/]"
    if check.disagree:
        return f" [bold red]{' and '.join(check.suspects)} differ[/]" if check.suspects else \
            " [bold red]strategies disagree[/]"
    return " strategies agree" if check.verdict == "AGREE" else " [yellow]strategies inconclusive[/]"


def image_table(results: list[ImageResult], alpha: float) -> Table:
    """One row per (scene, integrator): verdict, failing scales, mean ratio, relMSE, FLIP, seconds."""
    tested = results[0].engine if results else "tested"
    reference = next((name for r in results for name in r.references), "reference")
    table = Table(title=f"{tested} against {reference} (per-comparison α {alpha:.2g}, family-wise 0.01)",
                  box=box.SIMPLE_HEAD, padding=(0, 1), header_style="bold")
    for name in ("scene", "integrator", "verdict", "mean ratio", "relMSE", "FLIP", "min bias", "idiff",
                 f"s {tested}", f"s {reference}"):
        table.add_column(name, no_wrap=True)
    for r in results:
        # The first comparison is with the reference engine; a closed form's, if any, follows it.
        m = next(iter(r.comparisons.values()), None)
        if r.error is not None or m is None:  # a render failed: no comparison (the CLI prints why)
            table.add_row(r.case.scene, r.case.integrator, "[bold red]FAIL[/] render failed", "—", "—", "—", "—", idiff_short(r.idiff),
                          f"{r.tested.seconds['total']:.2f}" if r.tested else "—", "—")
            continue
        verdicts = _cell(r) + _oracle_cell(r) + _strategies_cell(r)
        table.add_row(r.case.scene, r.case.integrator, verdicts, f"{m.metrics['mean_ratio']:.4f}",
                      f"{m.metrics['relmse']:.1e}", f"{m.metrics['flip_mean']:.3f}", f"{m.detectable_bias:.1e}", idiff_short(r.idiff),
                      f"{r.tested.seconds['total']:.2f}", f"{next(iter(r.references.values())).seconds.get('total', 0):.2f}")
    table.caption = (f"mean ratio: {tested} / {reference} image mean; min bias: smallest relative bias of the image mean "
                     "detected half of the time; +exact: also compared with the closed form; +twin: also with the "
                     "reference's render of the scale twin (the same scene at another scale); s: wall seconds of all "
                     "the case's renders, loading included (a stored reference: those that made it)\n" + LEGEND)
    for r in results:  # where the bad pixels are: one line per case and distinct finding
        found: dict[str, list[str]] = {}
        for name, c in r.comparisons.items():
            if not c.finite.passed:
                found.setdefault(c.finite.summary, []).append(name)
            if not c.independent:
                found.setdefault(c.independence.summary, []).append(name)
        for summary, names in found.items():
            table.caption += f"\n{escape(r.case.key)} (against {', '.join(names)}): {escape(summary)}"
        if r.strategies is not None and r.strategies.verdict != "AGREE":
            table.caption += f"\n{escape(r.case.key)} strategies {r.strategies.verdict}: {escape(r.strategies.reason)}"
    return table
