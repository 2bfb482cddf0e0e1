"""A reference engine's invariance cells, stored beside its reference images.

How Mitsuba behaves under the invariances does not depend on the renderer under test, so, like its reference
images, its cells are rendered once (`mcval references`, at REFERENCE_SEED) and stored:
`references/<engine>/<scene>/invariance-<integrator>.json`, one file per case with every cell of it. A run
reuses a file only when its provenance matches what the run would render: the scene file and its meshes
(SHA-256), the engine's version, samples, batches, resolution, seed, the per-comparison level, the variants,
and the SHA-256 of the code that decides a cell (CHECK_SOURCES). Anything else (a missing, stale, damaged or
edited file) makes the run render that case and say why in one line. Only the references command writes them.
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path

from harness.engines.base import Engine
from harness.images.references import REFERENCE_SEED, REFERENCES_DIR, scene_hash
from harness.images.suite import ROOT
from harness.invariance.cell import Cell, InvarianceCase, VariantResult
from harness.invariance.check import applicable
from harness.invariance.signal import BaseSignal
from harness.invariance.variants import Invariance
from harness.project import SOURCE_ROOT
from harness.results import write_atomic

STORE_FORMAT = 2
#: The code a reference's cells depend on: the rewrites and what each must do, the comparisons and their
#: statistics, the integrators' mappings onto Mitsuba and the Mitsuba engine. A change to any of it makes
#: the stored cells stale.
CHECK_SOURCES = ("harness/invariance/check.py", "harness/invariance/cell.py", "harness/invariance/signal.py",
                 "harness/invariance/rewrite.py", "harness/invariance/variants.py", "harness/invariance/float32.py",
                 "harness/comparison", "harness/statistics", "harness/integrators",
                 "harness/engines/base.py", "harness/engines/mitsuba.py", "harness/engines/mitsuba_scene.py",
                 "harness/engines/mitsuba_direct.py", "harness/engines/scene_paths.py",
                 "harness/engines/written_scene.py", "harness/engines/white_materials.py")


def check_sha256(root: Path = SOURCE_ROOT) -> str:
    """SHA-256 of the sources of CHECK_SOURCES (each file's path and bytes, in path order), as the running
    harness has them."""
    files = []
    for source in CHECK_SOURCES:
        path = root / source
        files += sorted(path.rglob("*.py")) if path.is_dir() else [path]
    h = hashlib.sha256()
    for f in sorted(files):
        h.update(f.relative_to(root).as_posix().encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def stored_path(engine: Engine, case: InvarianceCase, folder: Path = REFERENCES_DIR) -> Path | None:
    """Where the case's cells by `engine` are stored; None for a scene outside the suite (a --scene file)."""
    scenes = ROOT / "scenes"
    if not case.scene.resolve().is_relative_to(scenes) or case.problem:
        return None
    return folder / engine.name / case.scene.stem / f"invariance-{case.integrator}.json"


def provenance(engine: Engine, case: InvarianceCase, chosen: list[Invariance], alpha: float, batches: int,
               check: str) -> dict:
    """What the cells of `case` by `engine` are rendered from; stored cells are reused only when it matches."""
    scene, digest = engine.scene_file(case.scene), scene_hash(case.scene)
    return {"format": STORE_FORMAT, "scene": case.scene.name, "scene_sha256": digest,
            "engine_scene_sha256": digest if scene == case.scene else scene_hash(scene),
            "integrator": case.integrator, "engine": engine.version(), "sampler": engine.sampler, "spp": case.spp,
            "res": case.res, "batches": batches, "seed": REFERENCE_SEED, "alpha": alpha,
            "variants": {inv.name: [v.label for v in inv.variants] for inv in chosen}, "check_sha256": check}


def _content_sha256(cells: list) -> str:
    return hashlib.sha256(json.dumps(cells, sort_keys=True).encode()).hexdigest()


def write_cells(engine: Engine, case: InvarianceCase, chosen: list[Invariance], cells: list[Cell], alpha: float,
                batches: int, folder: Path = REFERENCES_DIR) -> Path:
    """Store the cells of `case` (rendered at REFERENCE_SEED) with their provenance; returns the file."""
    path = stored_path(engine, case, folder)
    if path is None:
        raise ValueError(f"{case.scene}: not a scene of the suite; its cells are not stored")
    data = [c.to_json() for c in cells]
    meta = {"provenance": provenance(engine, case, chosen, alpha, batches, check_sha256()),
            "cells": data, "content_sha256": _content_sha256(data)}
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, json.dumps(meta, indent=1) + "\n")
    return path


@dataclass(frozen=True)
class StoredScale:
    """A scale's smallest p-value, as a stored comparison keeps it."""

    scale: str
    min_p: float


@dataclass(frozen=True)
class StoredComparison:
    """What a variant's stored comparison keeps of harness.comparison.compare.Comparison: what the reports read."""

    passed: bool
    failed_checks: list[str]
    scales: tuple[StoredScale, ...]
    detectable_bias: float | None


def _cell(d: dict, case: InvarianceCase, engine: str, chosen: dict[str, Invariance]) -> Cell:
    """A Cell from its to_json(); KeyError, TypeError or ValueError if it is not one."""
    inv = chosen[d["invariance"]]
    if d["engine"] != engine or d["scene"] != case.scene.stem or d["integrator"] != case.integrator:
        raise ValueError(f"a cell of {d['engine']} {d['scene']}:{d['integrator']}")
    by_label = {v.label: v for v in inv.variants}
    variants = []
    for v in d["variants"]:
        comparison = None
        if v["error"] is None:
            comparison = StoredComparison(bool(v["pass"]), [str(c) for c in v["failed_checks"]],
                                          tuple(StoredScale(str(s), float(p)) for s, p in v["min_p"].items()),
                                          v["detectable_bias"])
        variants.append(VariantResult(by_label[v["variant"]], comparison, float(v["ratio"]), v["error"],
                                      v["float32_limit"], v["dependence"]))
    base = BaseSignal.from_json(d["base"]) if d["base"] is not None else None
    return Cell(engine, inv.name, case, variants, d["base_error"], base, d["dependence"])


def read_cells(engine: Engine, case: InvarianceCase, chosen: list[Invariance], alpha: float, batches: int,
               check: str, folder: Path = REFERENCES_DIR) -> tuple[list[Cell] | None, str]:
    """The stored cells of `case`, or None and why not (one line naming the file)."""
    path = stored_path(engine, case, folder)
    if path is None:
        return None, f"{case.key}: not a scene of the suite, nothing stored"
    if not path.exists():
        return None, f"{_shown(path)}: not stored"
    result = _parse(path, engine, case, chosen, alpha, batches, check)
    return result if result[0] is not None else (None, f"{_shown(path)}: {result[1]}")


def _shown(path: Path) -> Path:
    """The path as a message names it: relative to the project where it is in it."""
    return path.relative_to(ROOT) if path.is_relative_to(ROOT) else path


def _parse(path: Path, engine: Engine, case: InvarianceCase, chosen: list[Invariance], alpha: float, batches: int,
           check: str) -> tuple[list[Cell] | None, str]:
    """read_cells of an existing file; the reason without the file's name."""
    try:
        meta = json.loads(path.read_bytes())
        expected = provenance(engine, case, chosen, alpha, batches, check)
        stored = meta["provenance"]
        changed = [k for k in expected if stored.get(k) != expected[k]]
        if changed:
            return None, f"stale ({', '.join(changed)} changed)"
        if _content_sha256(meta["cells"]) != meta["content_sha256"]:
            return None, "its cells do not match content_sha256 (edited or damaged)"
        by_name = {inv.name: inv for inv in chosen}
        cells = [_cell(d, case, engine.name, by_name) for d in meta["cells"]]
    except OSError as e:
        return None, f"unreadable ({e.strerror or e})"
    except (ValueError, KeyError, TypeError, AttributeError) as e:  # JSON errors are ValueErrors
        return None, f"not a stored cell file ({type(e).__name__}: {e})"
    if sorted(c.invariance for c in cells) != sorted(by_name):
        return None, f"holds cells of {', '.join(c.invariance for c in cells)}, not of {', '.join(by_name)}"
    return cells, ""


def stored_cells(engines: list[Engine], cases: list[InvarianceCase], invariances: list[Invariance], alpha: float,
                 batches: int, folder: Path = REFERENCES_DIR) -> tuple[dict[tuple[str, str], list[Cell]], list[str]]:
    """(engine name, case key) -> the stored cells of every case whose file matches; and one line for each
    case that has none (why it is rendered instead)."""
    check = check_sha256()
    known, misses = {}, []
    for engine in engines:
        for case in cases:
            cells, why = read_cells(engine, case, applicable(invariances, case), alpha, batches, check, folder)
            if cells is None:
                misses.append(why)
            else:
                known[(engine.name, case.key)] = cells
    return known, misses
