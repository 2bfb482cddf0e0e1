"""Mitsuba reference renders under references/, each with its provenance.

A reference is stored as its summary (what the tests need of its K batches):
`references/<scene>/<integrator>.exr` holds the mean image (R, G, B) and the
variance of that mean (variance.R/G/B) in float32; the `.json` beside it holds
the provenance and the tile and image batch statistics. A reference is reused
only when its provenance (the hash of the scene file and every mesh it names,
Mitsuba's version and variant, samples, batches, seed, resolution) matches what
the run asks for; otherwise the run renders a fresh one and says so. Only
`python -m harness references` (make references) writes them.
"""
from __future__ import annotations

import hashlib
import json
import re
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from harness.compare import SUMMARY_FORMAT, Summary, summarize
from harness.engines.base import Engine
from harness.image_suite import REFERENCE_SPP, ROOT, ImageCase
from harness.results import write_atomic
from harness.stats import TILE_SIZE
from harness.welch import BatchStats

REFERENCES_DIR = ROOT / "references"
REFERENCE_SEED = 1000
#: Batches of a reference: more than ours, so its own noise matters less.
REFERENCE_BATCHES = 16
#: Every scene is validated at this resolution (references stay small).
RESOLUTION = 128


@dataclass
class Reference:
    """A reference engine's summary of K batches, and what it cost."""

    summary: Summary
    spp: int
    seconds: dict[str, float]
    source: str


def scene_hash(path: Path) -> str:
    """SHA-256 of the scene file and of every file its filename properties name."""
    h = hashlib.sha256(path.read_bytes())
    for name in sorted(set(re.findall(r'name="filename"\s+value="([^"]+)"', path.read_text()))):
        mesh = path.parent / name
        h.update(name.encode())
        h.update(mesh.read_bytes() if mesh.exists() else b"missing")
    return h.hexdigest()


def expected_provenance(case: ImageCase, engine: Engine) -> dict:
    """What a reference for `case` must have been made from to be reused."""
    return {"scene": case.mitsuba_path.name, "scene_sha256": scene_hash(case.mitsuba_path),
            "integrator": case.integrator, "engine": engine.version(), "spp": REFERENCE_SPP[case.integrator],
            "batches": REFERENCE_BATCHES, "seed": REFERENCE_SEED, "resolution": RESOLUTION, "tile": TILE_SIZE,
            "summary_format": SUMMARY_FORMAT}


def reference_path(case: ImageCase) -> Path:
    return REFERENCES_DIR / case.scene / f"{case.integrator}.exr"


def _stats(d: dict, k: int) -> BatchStats:
    return BatchStats(np.array(d["mean"]), np.array(d["var_of_mean"]), k)


def load_reference(case: ImageCase, engine: Engine) -> tuple[Reference | None, str]:
    """The stored reference if its provenance matches, else None; and why."""
    import OpenEXR

    path = reference_path(case)
    meta_path = path.with_suffix(".json")
    if not path.exists() or not meta_path.exists():
        return None, "no stored reference"
    meta = json.loads(meta_path.read_text())
    expected = expected_provenance(case, engine)
    changed = [k for k, v in expected.items() if meta["provenance"].get(k) != v]
    if changed:
        return None, f"stored reference is stale ({', '.join(changed)} changed)"
    with OpenEXR.File(str(path)) as f:
        layers = f.channels()
        mean = layers["RGB"].pixels.astype(np.float64)
        var = layers["variance"].pixels.astype(np.float64)
    k = meta["provenance"]["batches"]
    summary = Summary(BatchStats(mean, var, k), _stats(meta["tile"], k), _stats(meta["image"], k), meta["provenance"]["tile"])
    return Reference(summary, meta["provenance"]["spp"], meta["seconds"], "stored reference"), "stored reference"


def render_reference(case: ImageCase, engine: Engine) -> Reference:
    """The reference engine's K batches for `case` at the reference budget, summarised."""
    result = engine.render(str(case.mitsuba_path), case.integrator, REFERENCE_SPP[case.integrator],
                           REFERENCE_BATCHES, REFERENCE_SEED, {"res": str(RESOLUTION)})
    return Reference(summarize(result.batches), result.spp, result.seconds, "rendered now")


def write_reference(case: ImageCase, engine: Engine, reference: Reference) -> Path:
    """Store a reference as references/<scene>/<integrator>.exr and .json, each written atomically."""
    import OpenEXR

    s = reference.summary
    channels = {"RGB": s.pixel.mean.astype(np.float32), "variance": s.pixel.var_of_mean.astype(np.float32)}
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    path = reference_path(case)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.tmp.exr")
    with OpenEXR.File(header, channels) as f:
        f.write(str(tmp))
    write_atomic(path, tmp.read_bytes())
    tmp.unlink()
    meta = {"provenance": expected_provenance(case, engine),
            "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
            "seconds": reference.seconds,
            "tile": {"mean": s.tile.mean.round(7).tolist(), "var_of_mean": s.tile.var_of_mean.tolist()},
            "image": {"mean": s.image.mean.tolist(), "var_of_mean": s.image.var_of_mean.tolist()}}
    write_atomic(path.with_suffix(".json"), json.dumps(meta) + "\n")
    return path
