"""The metamorphic check: each engine renders a scene and its rewritten variants as independent batches, and
each variant's batches, mapped back (divided by the expected factor, normals rotated back), must pass the
image suite's Welch tests against the base. No reference engine is needed: physics is the oracle. A base
without signal leaves its cells inconclusive, and batches that are one image where noise is expected fail
them (harness/invariance/signal.py).

Our renderer breaking an invariance fails the suite; a reference engine breaking one is a finding, reported
and stored, never a failure of the tested engine.
"""
from __future__ import annotations

import tempfile
import xml.etree.ElementTree as ET
import zlib
from concurrent.futures import Future
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable

import numpy as np

from harness.distributed.bundle import Bundle
from harness.distributed.executor import Executor, SerialExecutor, Status, Task
from harness.engines.base import Engine, RenderFailed
from harness.engines.render_thread import RenderThread
from harness.integrators import entry
from harness.comparison.compare import compare_summaries
from harness.comparison.independence_check import SideIndependence, varying_elements
from harness.comparison.summary import Summary, summarize
from harness.invariance.cell import Cell, InvarianceCase, VariantResult
from harness.invariance.float32 import float32_limit
from harness.invariance.reference_noise import judge_against_references
from harness.invariance.signal import BaseSignal, structure, widely
from harness.invariance.rewrite import rewrite, unscaled_bsdfs
from harness.engines.scene_paths import absolute_paths
from harness.invariance.variants import Invariance, Variant
from harness.statistics.constants import IMAGE_BATCHES, SIGNIFICANCE, sidak_level


#: How a cell whose task gave no value (its worker died) begins its base_error.
TASK_FAILED = "task failed"


def image_ratio(variant: np.ndarray, base: np.ndarray, signed: bool) -> float:
    """Mean of the mapped-back variant over the base's mean (of absolute values for signed images)."""
    f = np.abs if signed else (lambda x: x)
    den = f(base).mean(dtype=np.float64)
    return float(f(variant).mean(dtype=np.float64) / den) if den != 0 else float("nan")


def case_seed(engine: str, case: InvarianceCase, label: str, seed: int) -> int:
    """Independent seeds for the base and each variant, per engine and case."""
    return (zlib.crc32(f"{engine}|{case.key}|{label}".encode()) + 7919 * seed) % 2**31


def _reason(e: Exception, folder: Path) -> str:
    """One line saying why a render failed, naming a rewritten file by its name, not its scratch folder."""
    reason = e.reason if isinstance(e, RenderFailed) else f"{type(e).__name__}: {str(e).strip()[:200]}"
    return reason.replace(f"{folder}/", "")


@dataclass
class _Render:
    """One render of a cell group: the base scene or a variant's rewritten file, and its outcome."""

    path: Path
    label: str
    limit: str | None = None
    error: str | None = None
    future: Future | None = None


def run_cell_group(engine: Engine, case: InvarianceCase, invariances: list[Invariance], alpha: float, seed: int,
                   folder: Path, batches: int = IMAGE_BATCHES) -> list[Cell]:
    """One base render of `case` by `engine`, then every variant of every invariance against it. An engine
    that renders in another process renders the next image while this thread compares the last."""
    params = {"res": str(case.res)}
    the = entry(case.integrator)
    signed = the.signed
    cells = [Cell(engine.name, inv.name, case) for inv in invariances]
    if case.problem:
        for cell in cells:
            cell.base_error = case.problem
        return cells
    jobs = [(inv, cell, k, v) for inv, cell in zip(invariances, cells) for k, v in enumerate(inv.variants)]
    renders = [_Render(case.scene, "base")]
    for inv, cell, k, v in jobs:
        r = _Render(folder / f"{case.scene.stem}.{inv.name}.{k}.xml", f"{inv.name}{v.label}")
        try:
            rewrite(case.scene, r.path, v.kind, v.value)
            r.limit = float32_limit(r.path)
        except Exception as e:
            r.error = _reason(e, folder)
        renders.append(r)

    def render(r: _Render) -> np.ndarray:
        return engine.render(str(r.path), case.integrator, case.spp, batches,
                             case_seed(engine.name, case, r.label, seed), params).batches

    def result(i: int) -> np.ndarray | None:
        """Render i's batches (None with its error set); a variant's render starts the next variant's first
        where the engine renders elsewhere (the base's does not: without a base no variant is rendered)."""
        for r in renders[i : i + 1 + (1 if engine.renders_elsewhere and i > 0 else 0)]:
            if r.future is None and r.error is None:
                r.future = pool.submit(render, r)
        r = renders[i]
        if r.error is not None:
            return None
        try:
            return r.future.result()
        except Exception as e:
            r.error = _reason(e, folder)
            return None

    with RenderThread() as pool:
        base = result(0)
        if base is None:  # no base image: every cell of the case fails with the reason
            for cell in cells:
                cell.base_error = renders[0].error
            return cells
        base_summary = summarize(base)
        signal = BaseSignal.of(base, base_summary)
        for cell in cells:
            cell.base, cell.dependence = signal, signal.unused_seed(the)
        has_environment = any(e.get("type") == "constant" for e in ET.parse(case.scene).getroot().iter("emitter"))
        for i, (inv, cell, _, v) in enumerate(jobs, start=1):
            out = result(i)
            if out is None:
                cell.variants.append(VariantResult(v, None, float("nan"), renders[i].error, renders[i].limit))
                continue
            mapped = v.expected(the, out.astype(np.float64), has_environment)
            summary = summarize(mapped)
            comparison = compare_summaries(summary, base_summary, alpha, signed=signed,
                                           samples=(case.spp, case.spp), metrics=False, tile_power=False)
            cell.variants.append(VariantResult(v, comparison, image_ratio(mapped, base, signed), None,
                                               renders[i].limit, variant_alike(summary, base_summary)))
    return cells


def variant_alike(variant: Summary, base: Summary) -> str | None:
    """Why a variant's batches are not independent, or None: all one image where the base's, of the same engine
    and estimator, vary widely, while the variant's image varies (a black variant is the comparison's to fail)."""
    side = SideIndependence(variant.dependence, varying_elements(base), int(base.pixel.mean.size), judge_alike=True)
    if not (side.alike and widely(structure(variant.pixel.mean), side.elements)):
        return None
    return side.reason("variant", "base")


def comparisons_of(cases: list[InvarianceCase], invariances: list[Invariance]) -> int:
    """How many variant comparisons one engine makes (the family its level is split over)."""
    return sum(len(inv.variants) for c in cases for inv in applicable(invariances, c))


def family_alpha(cases: list[InvarianceCase], invariances: list[Invariance]) -> float:
    """The per-comparison level: one engine's comparisons share a family-wise rate of SIGNIFICANCE (Sidak)."""
    return sidak_level(SIGNIFICANCE, comparisons_of(cases, invariances))


def run_invariances(engines: list[Engine], cases: list[InvarianceCase], invariances: list[Invariance],
                    seed: int = 0, on_status: Callable[[Status], None] | None = None,
                    batches: int = IMAGE_BATCHES, executor: Executor | None = None,
                    seeds: dict[str, int] | None = None, known: dict[tuple[str, str], list[Cell]] | None = None,
                    alpha: float | None = None) -> tuple[list[Cell], float]:
    """Every engine x case x invariance that applies to the case's integrator, one task per engine and case
    on `executor` (default: here, one after another). Each engine's comparisons share a family-wise
    false-alarm rate of SIGNIFICANCE (Sidak); returns the cells, in a fixed order, and the per-comparison level.
    `seeds`: an engine's seed by name (default `seed`); `known`: the cells of (engine name, case key) already
    known (a reference engine's stored ones), which are not rendered again; `alpha`: the per-comparison level
    (default: family_alpha of these cases, a narrower family than the suite's for a subset). Base batches
    that are one image are judged against an engine among them that draws the same estimator
    (judge_against_references)."""
    from harness.distributed.bundle import bundle_files

    executor = executor or SerialExecutor()
    seeds, known = seeds or {}, known or {}
    alpha = family_alpha(cases, invariances) if alpha is None else alpha
    pairs = [(engine, case) for engine in engines for case in cases]
    todo = [(engine, case) for engine, case in pairs if (engine.name, case.key) not in known]
    bundles = {}
    if executor.ships_files:
        for _, case in todo:
            if case.scene not in bundles:
                bundles[case.scene] = executor.share(bundle_files(case.scene.resolve().parent, [case.scene.resolve()]))
    tasks = [Task(f"{engine.name} {case.key}", cell_group_task,
                  (engine, case, applicable(invariances, case), alpha, seeds.get(engine.name, seed), batches,
                   bundles.get(case.scene)))
             for engine, case in todo]
    rendered: dict[tuple[str, str], list[Cell]] = {}
    for task, outcome in zip(tasks, executor.run(tasks, on_status)):
        engine, case, chosen = task.args[:3]
        # A task that failed (its worker died): its cells fail with the reason.
        rendered[(engine.name, case.key)] = outcome.value if outcome.ok else [
            Cell(engine.name, inv.name, case, base_error=f"{TASK_FAILED}: {outcome.error}") for inv in chosen]
    cells: list[Cell] = []
    for engine, case in pairs:
        key = (engine.name, case.key)
        cells += known[key] if key in known else rendered.get(key, [])
    judge_against_references(cells, engines)
    return cells, alpha


def applicable(invariances: list[Invariance], case: InvarianceCase) -> list[Invariance]:
    """The invariances that can change the image of the case's integrator. Halving the diffuse reflectances
    halves an image linear in them only where no other BSDF reflects light: on a scene with one, that check is
    not made (an integrator independent of the reflectance is still checked)."""
    chosen = [inv for inv in invariances if inv.applies_to(entry(case.integrator))]
    if "reflectance" in entry(case.integrator).linear_in and any(inv.name == "reflectance" for inv in chosen):
        try:
            root = ET.parse(case.scene).getroot()
            absolute_paths(root, case.scene)
        except (ET.ParseError, OSError, ValueError):
            return chosen  # the renderer reports a broken file as the case's failure
        if unscaled_bsdfs(root):
            chosen = [inv for inv in chosen if inv.name != "reflectance"]
    return chosen


def cell_group_task(engine: Engine, case: InvarianceCase, chosen: list[Invariance], alpha: float, seed: int,
                    batches: int, bundle: Bundle | None = None) -> list[Cell]:
    """run_cell_group as a task: with a bundle, on the bundle's copy of the scene (and its meshes)."""
    if not chosen:
        return []
    local = case if bundle is None else replace(case, scene=bundle.materialize() / case.scene.name)
    with tempfile.TemporaryDirectory(prefix="mcval-invariance-") as tmp:
        cells = run_cell_group(engine, local, chosen, alpha, seed, Path(tmp), batches)
    for cell in cells:
        cell.case = case
    return cells
