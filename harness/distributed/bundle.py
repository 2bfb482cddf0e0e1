"""Files sent by content: a scene, the meshes it names and its stored reference, as bytes under their
paths relative to the project root, so that a worker with none of them (another machine) renders the
same files. A worker writes a bundle once into its own cache folder, named by the bundle's digest."""
from __future__ import annotations

import hashlib
import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

FILENAME = re.compile(r'name="filename"\s+value="([^"]+)"')


@dataclass(frozen=True)
class Bundle:
    files: tuple[tuple[str, bytes], ...]   # (path relative to the root, content), sorted by path
    digest: str                            # SHA-256 over paths and contents

    def materialize(self, cache: Path | None = None) -> Path:
        """The root folder holding these files (written on first use; concurrent writers are safe)."""
        root = (cache or Path(tempfile.gettempdir()) / f"mcval-bundles-{os.getuid()}") / self.digest
        done = root / ".complete"
        if done.exists():
            return root
        for rel, data in self.files:
            path = root / rel
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
            tmp.write_bytes(data)
            os.replace(tmp, path)
        done.touch()
        return root


def bundle_files(root: Path, scenes: list[Path], extra: dict[str, Path] | None = None) -> Bundle:
    """Scene files under `root` with every file they name, and `extra` files (relative path: file), read now;
    missing files are left out (the worker then finds them missing, as this machine would)."""
    wanted: dict[str, Path] = {rel: p for rel, p in (extra or {}).items() if p.is_file()}
    for path in scenes:
        if not path.exists():
            continue
        wanted[str(path.relative_to(root))] = path
        if path.suffix == ".xml":
            for name in FILENAME.findall(path.read_text(errors="replace")):
                named = (path.parent / name).resolve()
                if named.is_file() and named.is_relative_to(root):
                    wanted[str(named.relative_to(root))] = named
    files = tuple(sorted((rel, p.read_bytes()) for rel, p in wanted.items()))
    h = hashlib.sha256()
    for rel, data in files:
        h.update(rel.encode() + b"\0" + len(data).to_bytes(8, "little") + data)
    return Bundle(files, h.hexdigest())
