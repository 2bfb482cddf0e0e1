"""Reference renders under references/<engine>/, each with its provenance.

A reference is stored as its summary (what the tests need of its K batches), under the name of the engine
that rendered it: `references/<engine>/<scene>/<integrator>.exr` holds the mean image (R, G, B) and the
variance of that mean (variance.R/G/B) in float32; the `.json` beside it holds
the provenance and the tile and image batch statistics. A reference is reused
only when its provenance (the hash of the scene file and every mesh it names,
Mitsuba's version and variant, how it renders the integrator, samples, batches, seed, resolution) matches what
the run asks for; otherwise the run renders a fresh one and says so. Only
`mcval references` (make references) writes them.

Every file is checked when read. The .json records the size and SHA-256 of the
.exr (so damaged bytes never reach the EXR decoder) and `content_sha256`, the
SHA-256 of every array of the summary as stored; anything wrong (a file that
does not parse, a field missing or of the wrong shape, a missing layer, a wrong
size, a non-finite value, a hash that does not match) makes `load_reference`
return None with one line naming the file, and the run renders a fresh one.
"""
from __future__ import annotations

import hashlib
import json
import re
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from harness.comparison.summary import SUMMARY_FORMAT, Summary, summarize
from harness.engines.base import Engine
from harness.images.suite import REFERENCE_SPP, ROOT, USER, ImageCase
from harness.results import write_atomic
from harness.statistics.constants import TILE_SIZE
from harness.statistics.welch import BatchStats

REFERENCES_DIR = ROOT / "references"
REFERENCE_SEED = 1000
#: Batches of a reference: more than the tested engine's, so its own noise matters less.
REFERENCE_BATCHES = 16
#: Every scene is validated at this resolution (references stay small).
RESOLUTION = 128


def render_params(case: ImageCase) -> dict[str, str]:
    """The parameters every render of `case` is given: the suite's resolution for the suite's scenes; none for
    a --scene file, whose prepared copy declares the size the run asked for (harness/images/user_scenes.py)."""
    return {} if case.group == USER else {"res": str(RESOLUTION)}


#: The source of a reference that is the integrator's closed form (harness/engines/analytic.py).
CLOSED_FORM = "closed form"


@dataclass
class Reference:
    """A reference engine's summary of K batches, and what it cost."""

    summary: Summary
    spp: int
    seconds: dict[str, float]
    source: str


def scene_hash(path: Path) -> str:
    """SHA-256 of the scene file and of every regular file its filename properties name (a device or a pipe
    is hashed by its name only: it would be read without end)."""
    h = hashlib.sha256(path.read_bytes())
    for name in sorted(set(re.findall(r'name="filename"\s+value="([^"]+)"', path.read_text()))):
        mesh = path.parent / name
        h.update(name.encode())
        if mesh.is_file():
            h.update(mesh.read_bytes())
        else:
            h.update(b"not a regular file" if mesh.exists() else b"missing")
    return h.hexdigest()


def expected_provenance(case: ImageCase, engine: Engine) -> dict:
    """What a reference for `case` must have been made from to be reused."""
    scene = engine.scene_file(case.path)
    return {"scene": scene.name, "scene_sha256": scene_hash(scene),
            "integrator": case.integrator, "engine": engine.version(),
            # Its plugin and what its copy of the scene changes: a new mapping makes a new image.
            "mapping": engine.integrator_mapping(case.integrator), "spp": REFERENCE_SPP[case.integrator],
            "batches": REFERENCE_BATCHES, "seed": REFERENCE_SEED, "resolution": RESOLUTION, "tile": TILE_SIZE,
            "summary_format": SUMMARY_FORMAT}


def reference_path(case: ImageCase, engine: Engine) -> Path:
    """Where the case's stored reference by `engine` is: references/<engine>/<scene>/<integrator>.exr under
    the project, or in a worker's copy of the files."""
    # A user's scene (--scene) has none stored: its prepared copy's folder holds no references/.
    folder = REFERENCES_DIR if case.root == ROOT and case.group != USER else case.root / "references"
    return folder / engine.name / case.scene / f"{case.integrator}.exr"


def summary_sha256(summary: Summary) -> str:
    """SHA-256 of the arrays a reference stores, as stored: the pixel mean and variance as float32, the
    tile and image statistics as float64 (each array's name and shape included)."""
    h = hashlib.sha256()
    for name, stats, dtype in (("pixel", summary.pixel, "<f4"), ("tile", summary.tile, "<f8"),
                               ("image", summary.image, "<f8")):
        for part in ("mean", "var_of_mean"):
            a = np.ascontiguousarray(getattr(stats, part), dtype=dtype)
            h.update(f"{name}.{part}{a.shape}".encode())
            h.update(a.tobytes())
    return h.hexdigest()


class _Damaged(Exception):
    """A stored reference file that cannot be used; the message is one line naming the file."""

    def __init__(self, path: Path | str, what: str) -> None:
        super().__init__(f"{path}: {' '.join(str(what).split())}")


def _read_meta(meta_path: Path) -> dict:
    """The .json as an object with a `provenance` object, or _Damaged."""
    try:
        meta = json.loads(meta_path.read_bytes())
    except OSError as e:
        raise _Damaged(meta_path, f"unreadable ({e.strerror or e})") from None
    except ValueError as e:  # JSONDecodeError, UnicodeDecodeError
        raise _Damaged(meta_path, f"not valid JSON, truncated or damaged ({e})") from None
    if not isinstance(meta, dict):
        raise _Damaged(meta_path, f"not a JSON object but a {type(meta).__name__}")
    if not isinstance(meta.get("provenance"), dict):
        raise _Damaged(meta_path, "no 'provenance' object")
    return meta


def _check_values(path: Path, what: str, mean: np.ndarray, var: np.ndarray) -> None:
    bad = int((~np.isfinite(mean)).sum() + (~np.isfinite(var)).sum())
    if bad:
        raise _Damaged(path, f"{what}: non-finite values: {bad}")
    if (var < 0).any():
        raise _Damaged(path, f"{what}: negative variances: {int((var < 0).sum())}")


def _json_stats(meta: dict, name: str, shape: tuple[int, ...], k: int, meta_path: Path) -> BatchStats:
    """The `name` statistics of the .json, checked: numbers, of `shape`, finite, variances >= 0."""
    d = meta.get(name)
    if not isinstance(d, dict) or "mean" not in d or "var_of_mean" not in d:
        raise _Damaged(meta_path, f"no '{name}' object with 'mean' and 'var_of_mean'")
    try:
        mean, var = np.array(d["mean"], dtype=np.float64), np.array(d["var_of_mean"], dtype=np.float64)
    except (TypeError, ValueError):
        raise _Damaged(meta_path, f"'{name}' statistics are not arrays of numbers") from None
    if mean.shape != shape or var.shape != shape:
        raise _Damaged(meta_path, f"'{name}' statistics have shapes {mean.shape} and {var.shape}, not {shape}")
    _check_values(meta_path, f"'{name}' statistics", mean, var)
    return BatchStats(mean, var, k)


def _read_exr(path: Path, meta: dict, meta_path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The mean and variance layers, after the file's size and SHA-256 matched those the .json records."""
    from harness.exr import read_layers

    size, digest = meta.get("exr_bytes"), meta.get("exr_sha256")
    if not isinstance(size, int) or not isinstance(digest, str):
        raise _Damaged(meta_path, "no 'exr_bytes' and 'exr_sha256' of the .exr")
    data = path.read_bytes()
    if len(data) < size:
        raise _Damaged(path, f"truncated or replaced ({len(data)} of the {size} bytes written)")
    if len(data) != size or hashlib.sha256(data).hexdigest() != digest:
        raise _Damaged(path, f"not the file written ({len(data)} bytes, {size} written; SHA-256 differs from "
                             f"the one in {meta_path.name}): damaged or edited")
    try:
        layers, _ = read_layers(path)
        missing = [name for name in ("RGB", "variance") if name not in layers]
        if missing:
            raise _Damaged(path, f"no {' or '.join(missing)} layer (has {', '.join(layers) or 'none'})")
        mean = layers["RGB"].astype(np.float64)
        var = layers["variance"].astype(np.float64)
    except _Damaged:
        raise
    except Exception as e:  # the decoder's own errors: RuntimeError, ValueError, ...
        raise _Damaged(path, f"not a readable EXR ({e})") from None
    expected = (RESOLUTION, RESOLUTION, 3)
    if mean.shape != expected or var.shape != expected:
        raise _Damaged(path, f"layers of shapes {mean.shape} and {var.shape}, not {expected} "
                             f"(every scene is validated at {RESOLUTION}x{RESOLUTION})")
    _check_values(path, "pixels", mean, var)
    return mean, var


def _read_summary(path: Path, meta_path: Path, meta: dict) -> tuple[Summary, dict]:
    """The stored summary and seconds, every array checked and the content hash compared."""
    provenance = meta["provenance"]
    k, tile = provenance["batches"], provenance["tile"]
    seconds = meta.get("seconds")
    if not isinstance(seconds, dict) or not all(isinstance(v, (int, float)) for v in seconds.values()):
        raise _Damaged(meta_path, "no 'seconds' object of numbers")
    if not isinstance(meta.get("content_sha256"), str):
        raise _Damaged(meta_path, "no 'content_sha256'")
    mean, var = _read_exr(path, meta, meta_path)
    tiles = (-(-RESOLUTION // tile), -(-RESOLUTION // tile), 3)
    summary = Summary(BatchStats(mean, var, k), _json_stats(meta, "tile", tiles, k, meta_path),
                      _json_stats(meta, "image", (3,), k, meta_path), tile)
    if summary_sha256(summary) != meta["content_sha256"]:
        raise _Damaged(f"{path} and {meta_path}", "summary does not match its stored arrays (edited or damaged: "
                                                  "content_sha256 differs)")
    return summary, seconds


def load_reference(case: ImageCase, engine: Engine) -> tuple[Reference | None, str]:
    """The stored reference if its provenance matches and its files are sound, else None; and why, in
    one line ("<path>: <what is wrong>" for a damaged file). Never raises for a bad file."""
    path = reference_path(case, engine)
    meta_path = path.with_suffix(".json")
    if not path.exists() and not meta_path.exists():
        return None, "no stored reference"
    expected = expected_provenance(case, engine)
    try:
        for p, other in ((path, meta_path), (meta_path, path)):
            if not p.exists():
                raise _Damaged(p, f"missing (while {other.name} is there)")
        meta = _read_meta(meta_path)
        changed = [k for k, v in expected.items() if meta["provenance"].get(k) != v]
        if changed:
            return None, f"stored reference is stale ({', '.join(changed)} changed)"
        summary, seconds = _read_summary(path, meta_path, meta)
    except _Damaged as e:
        return None, str(e)
    except Exception as e:  # whatever else a damaged file may cause, still one line naming it
        return None, str(_Damaged(path, f"unreadable ({type(e).__name__}: {e})"))
    return Reference(summary, expected["spp"], seconds, "stored reference"), "stored reference"


def render_reference(case: ImageCase, engine: Engine) -> Reference:
    """The reference engine's K batches for `case` at the reference budget, summarised."""
    result = engine.render(str(engine.scene_file(case.path)), case.integrator, REFERENCE_SPP[case.integrator],
                           REFERENCE_BATCHES, REFERENCE_SEED, render_params(case))
    return Reference(summarize(result.batches), result.spp, result.seconds, "rendered now")


def write_reference(case: ImageCase, engine: Engine, reference: Reference) -> Path:
    """Store a reference as references/<engine>/<scene>/<integrator>.exr and .json, each written atomically."""
    from harness.exr import write_layers

    s = reference.summary
    # Exactly what will be read back: float32 pixels, tile means rounded to 7 decimals.
    stored = Summary(BatchStats(s.pixel.mean.astype(np.float32), s.pixel.var_of_mean.astype(np.float32), s.pixel.k),
                     BatchStats(s.tile.mean.round(7), s.tile.var_of_mean, s.tile.k), s.image, s.tile_size)
    channels = {"RGB": stored.pixel.mean, "variance": stored.pixel.var_of_mean}
    path = reference_path(case, engine)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.tmp.exr")
    write_layers(tmp, channels)
    exr = tmp.read_bytes()
    write_atomic(path, exr)
    tmp.unlink()
    meta = {"provenance": expected_provenance(case, engine),
            "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
            "seconds": reference.seconds,
            "exr_bytes": len(exr), "exr_sha256": hashlib.sha256(exr).hexdigest(),
            "content_sha256": summary_sha256(stored),
            "tile": {"mean": stored.tile.mean.tolist(), "var_of_mean": stored.tile.var_of_mean.tolist()},
            "image": {"mean": stored.image.mean.tolist(), "var_of_mean": stored.image.var_of_mean.tolist()}}
    write_atomic(path.with_suffix(".json"), json.dumps(meta) + "\n")
    return path
