"""Plugins as files: the *.py files of the folders an environment variable names, each defining one object
(an integrator's ENTRY, an engine's ENGINE), so that a test or a user adds one without editing the harness."""
from __future__ import annotations

import importlib.util
import os
from pathlib import Path


def plugin_objects(folders: str, attribute: str, env: str) -> list[tuple[Path, object]]:
    """(file, its `attribute`) for every *.py file not starting with "_" in the os.pathsep-separated
    `folders` (the value of $`env`), in name order. ValueError naming the folder or file if a folder is
    missing or a file lacks `attribute`."""
    found = []
    for folder in (Path(p) for p in folders.split(os.pathsep) if p):
        if not folder.is_dir():
            raise ValueError(f"{env}: {folder} is not a folder")
        for path in sorted(folder.glob("*.py")):
            if path.name.startswith("_"):
                continue
            spec = importlib.util.spec_from_file_location(f"mcval_{attribute.lower()}_{path.stem}", path)
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            if not hasattr(module, attribute):
                raise ValueError(f"{path}: no {attribute} (every .py file in a {env} folder defines one)")
            found.append((path, getattr(module, attribute)))
    return found
