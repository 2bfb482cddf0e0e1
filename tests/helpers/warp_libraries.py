"""C warp libraries built for a test: a source exporting the ABI of include/mcval_warps.h, compiled as a user
would (`cc -O2 -shared -fPIC`), loaded as `--warp-library` loads it."""
from __future__ import annotations

import subprocess
from pathlib import Path

from harness.engines.warp_library import WarpLibraryEngine

INCLUDE = Path(__file__).resolve().parents[2] / "include"


def build_warp_library(source: Path, folder: Path) -> Path:
    """Compile `source` (C) into folder/lib<stem>.so; the compiler's own message if it fails."""
    library = folder / f"lib{source.stem}.so"
    done = subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-Wall", "-Wextra", f"-I{INCLUDE}", str(source), "-o",
                           str(library), "-lm"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return library


def warp_library(source: Path, folder: Path) -> WarpLibraryEngine:
    """build_warp_library, loaded."""
    return WarpLibraryEngine(build_warp_library(source, folder))
