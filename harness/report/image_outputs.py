"""What an image run leaves behind: report.html, junit.xml and the images part of results.json."""
from __future__ import annotations

import traceback
from pathlib import Path

import numpy as np

from harness.foreign_text import one_line
from harness.images.evaluate import failure
from harness.images.result import ImageResult
from harness.images.regression import compare_runs, load_baseline
from harness.report.image_html import entry_html, report_html, reproduce_command
from harness.report.junit import junit_xml
from harness.results import write_atomic, write_json, write_npz


def _case_outputs(r: ImageResult, run_dir: Path, run: dict | None) -> None:
    """What the case itself puts into results.json, report.html and, failed, results/<run>/images/."""
    entry = r.to_json()
    entry_html(r, run)
    if not r.passed and r.error is None:  # (a failed render has no arrays; its entry says why)
        # What is needed to see why: both means, the variances and the p-value maps.
        stem = run_dir / "images" / f"{r.case.scene}_{r.case.integrator}"
        arrays = {"tested_mean": r.tested.mean, "tested_batches": r.tested.batches}
        for name, ref in r.references.items():
            arrays[f"{name}_mean"] = ref.summary.pixel.mean
            arrays[f"{name}_var_of_mean"] = ref.summary.pixel.var_of_mean
            for scale in r.comparisons[name].scales:
                arrays[f"{name}_p_{scale.scale}"] = scale.p_map
            finite = r.comparisons[name].finite
            if not finite.passed:  # 1: NaN, Inf or negative in the tested image, 2: in the reference, 3: both
                arrays[f"{name}_bad_pixels"] = (finite.test.mask + 2 * finite.reference.mask).astype(np.uint8)
        write_npz(stem.with_suffix(".npz"), **arrays)
        write_json(stem.with_suffix(".json"), {**entry, "reproduce": reproduce_command(r, run)})


def _reportable(r: ImageResult, run_dir: Path, run: dict | None) -> None:
    """`r`'s own part of the outputs written; where it cannot be, `r` failed (in place) with one line saying
    why and its traceback for the run's log: one case's report never ends the run."""
    try:
        _case_outputs(r, run_dir, run)
    except Exception as e:
        r.tested, r.references, r.reference_fit = None, {}, None
        r.decision = failure(one_line(f"report: {type(e).__name__}: {e}"))
        r.traceback = traceback.format_exc()


def write_image_outputs(run_dir: Path, results: list[ImageResult], alpha: float, warps: dict | None,
                        meta: dict, baseline_path: Path | None, invariance: dict | None = None,
                        run: dict | None = None) -> dict:
    """Writes report.html and junit.xml; returns the results.json fields (images, regression).
    `invariance`: the same run's invariance block (results.json's), shown in the report and linked; `run`: the
    run's invocation (report/reproduce.py), repeated by every reproduce line."""
    for r in results:
        _reportable(r, run_dir, run)
    images = [r.to_json() for r in results]
    for r, entry in zip(results, images):
        if not r.passed and r.error is None:  # written by _case_outputs
            stem = run_dir / "images" / f"{r.case.scene}_{r.case.integrator}"
            entry["data"] = str(stem.relative_to(run_dir)) + ".npz"
    baseline = load_baseline(baseline_path) if baseline_path else None
    regression = compare_runs(images, baseline) if baseline else None
    baseline_name = baseline.get("run") if baseline else None
    bench = run_dir.parent / "bench-latest" / "bench.html"
    bench_href = "../bench-latest/bench.html" if bench.exists() else None
    calibration = run_dir.parent / "calibration-latest" / "calibration.html"
    calibration_href = "../calibration-latest/calibration.html" if calibration.exists() else None
    write_atomic(run_dir / "report.html",
                 report_html(results, alpha, warps, meta, regression, baseline_name, bench_href, invariance,
                             calibration_href, run))
    write_atomic(run_dir / "junit.xml", junit_xml(results, warps["warps"] if warps else None, meta))
    return {"images": images, "image_alpha": alpha, "regression": regression, "baseline": baseline_name,
            "image_meta": meta, "invocation": run}
