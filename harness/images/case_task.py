"""One image case as a task that runs anywhere: in this process, or on a Dask worker with the scene's
files sent by content. What comes back is the case's result without our batches when it passed (the
report needs only their means), and the messages the case printed."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from harness.distributed.bundle import Bundle, bundle_files
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine
from harness.images.references import RESOLUTION, reference_path
from harness.images.suite import ROOT, ImageCase


@dataclass
class CaseJob:
    case: ImageCase
    seed: int                # the case's own seed (run.case_seed)
    alpha: float             # per-comparison level of the whole run
    run_seed: int
    closed_form: bool        # whether the analytic engine renders this case too
    test: Engine             # the engine under test
    reference: Engine


def share_scene_bundles(executor, cases, engines: Sequence[Engine]) -> dict[str, object]:
    """Per scene of `cases`, a handle to its bundle on the executor's cluster, each sent once; nothing
    for an executor that runs here (its tasks read the files in place). `engines`: those that will render
    the cases (each may read its own scene file, and its stored references)."""
    bundles: dict[str, object] = {}
    if executor.ships_files:
        for case in cases:
            if case.scene not in bundles:
                bundles[case.scene] = executor.share(scene_bundle(case, engines))
    return bundles


def on_files(case: ImageCase, bundle: Bundle | None) -> ImageCase:
    """`case` reading the bundle's copy of its files (written on first use), or its own without one."""
    return case if bundle is None else replace(case, root=bundle.materialize())


def scene_bundle(case: ImageCase, engines: Sequence[Engine] = ()) -> Bundle:
    """The files every case of `case.scene` reads: its scene file and each engine's (Engine.scene_file),
    their meshes, and each engine's stored references of the scene."""
    extra = {}
    for engine in engines:
        stored = reference_path(case, engine).parent
        if stored.is_dir():
            extra.update({str(p.relative_to(ROOT)): p for p in sorted(stored.glob("*"))})
    files = list(dict.fromkeys([case.path, *(e.scene_file(case.path) for e in engines)]))
    return bundle_files(ROOT, files, extra)


def run_case_job(job: CaseJob, bundle: Bundle | None = None):
    """(ImageResult, messages). With a bundle, the case reads the bundle's copy of its files."""
    from harness.images.run import _run_case

    case = on_files(job.case, bundle)
    messages: list[str] = []
    result = _run_case(case, job.test, job.reference, AnalyticEngine() if job.closed_form else None,
                       {"res": str(RESOLUTION)}, job.seed, job.alpha, job.run_seed, messages.append)
    result.case = job.case
    if result.ours is not None and (result.passed or result.error is not None):
        result.ours = result.ours.light()  # a failed comparison keeps its batches for results/<run>/images/
    return result, messages


def reference_task(case: ImageCase, engine: Engine, bundle: Bundle | None = None):
    """The reference engine's render of `case` at the reference budget, summarised (references command)."""
    from harness.images.references import render_reference

    return render_reference(on_files(case, bundle), engine)
