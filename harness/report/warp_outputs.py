"""What a warp run leaves behind: JSON, the HTML page, and the data of every failure."""
from __future__ import annotations

from pathlib import Path

from harness.report.junit import junit_xml
from harness.report.warp_html import warp_report_html
from harness.results import write_atomic, write_json, write_npz
from harness.report.reproduce import reproduce_line
from harness.warps.suite import WarpSpec
from harness.warps.evaluate import WarpResult


def warp_payload(results: list[WarpResult], level: float, meta: dict) -> dict:
    """The warps part of results.json: "pass" (no warp fails), "verdict" (FAIL, else WARN if a warp warns,
    else PASS), the per-test level, and each warp with its checks."""
    verdicts = {r.verdict for r in results}
    verdict = next((v for v in ("FAIL", "WARN") if v in verdicts), "PASS")
    return {"pass": all(r.passed for r in results), "verdict": verdict, "level": level, "meta": meta,
            "warps": [r.to_json() for r in results]}


def write_warp_outputs(run_dir: Path, specs: list[WarpSpec], results: list[WarpResult], level: float,
                       meta: dict, seed: int, run: dict | None = None) -> dict[str, Path]:
    """Write warps.html, junit.xml and, for each failing warp, warps/<key>.npz with its histograms and checks; `run`: the
    run's invocation (report/reproduce.py), repeated by each reproduce line."""
    reproduce, data_files = {}, {}
    for spec, r in zip(specs, results):
        reproduce[r.label] = reproduce_line("warps", ["--only", spec.key], seed, run)
        if not r.passed:
            path = run_dir / "warps" / f"{spec.key.replace(':', '_')}.npz"
            if not r.failure:  # a warp that crashed has no histograms
                write_npz(path, observed=r.observed, expected=r.expected, reference_observed=r.reference_observed,
                          target_observed=r.target_observed, target_expected=r.target_expected)
            write_json(path.with_suffix(".json"), {**r.to_json(), "reproduce": reproduce[r.label]})
            data_files[r.label] = str((path.with_suffix(".json") if r.failure else path).relative_to(run_dir))
    html_path = write_atomic(run_dir / "warps.html", warp_report_html(results, level, meta, reproduce, data_files))
    # The warps' junit.xml; a run with images as well (validate) writes one of both over it.
    write_atomic(run_dir / "junit.xml", junit_xml([], [r.to_json() for r in results]))
    return {"html": html_path, **{k: run_dir / v for k, v in data_files.items()}}
