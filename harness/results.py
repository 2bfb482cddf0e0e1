"""Run folders under results/ and files written whole or not at all."""
from __future__ import annotations

import json
import os
import tempfile
from datetime import datetime
from pathlib import Path
from typing import Any

import numpy as np

from harness.foreign_text import xml_safe


def point_link(link: Path, target: Path) -> None:
    """Make `link` a symlink to `target` (a sibling folder), replacing any older link atomically."""
    tmp = link.with_name(f".{link.name}-{os.getpid()}")
    tmp.unlink(missing_ok=True)
    tmp.symlink_to(target.name)
    os.replace(tmp, link)


def latest_run(root: str | Path = "results") -> str | None:
    """The name of the run results/latest points at (the newest complete run), or None if there is none."""
    link = Path(root) / "latest"
    return os.readlink(link) if link.is_symlink() else None


def new_run_dir(root: str | Path = "results") -> Path:
    """A fresh folder results/<date>-<time>[-n]. results/latest is left alone: it is moved to a run
    (`point_link`) only once that run has written its results."""
    root = Path(root)
    root.mkdir(parents=True, exist_ok=True)
    stamp = datetime.now().strftime("%Y%m%d-%H%M%S")
    run, n = root / stamp, 1
    while run.exists():
        n += 1
        run = root / f"{stamp}-{n}"
    run.mkdir()
    return run


def write_atomic(path: str | Path, data: bytes | str) -> Path:
    """Write to a temporary file beside `path`, then rename: readers never see half a file. Text is written as
    UTF-8 with every character XML 1.0 forbids escaped (foreign_text.xml_safe), so that a renderer's message
    in it leaves results.json, a page or junit.xml readable."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(xml_safe(data).encode() if isinstance(data, str) else data)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    return path


def _plain(x: Any) -> Any:
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, float) and not np.isfinite(x):
        return str(x)  # JSON has no inf or nan
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    return x


def write_json(path: str | Path, payload: dict) -> Path:
    """JSON (numpy scalars made plain, inf/nan as strings), written atomically."""
    return write_atomic(path, json.dumps(_plain(payload), indent=2) + "\n")


def write_npz(path: str | Path, **arrays: np.ndarray) -> Path:
    """A compressed .npz, written atomically."""
    import io
    buf = io.BytesIO()
    np.savez_compressed(buf, **{k: v for k, v in arrays.items() if v is not None})
    return write_atomic(path, buf.getvalue())
