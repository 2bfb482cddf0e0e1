"""Finding the integrator entries and matching them with the list of integrators the tested engine renders.

Entries are the modules of this package with an `ENTRY`, plus every *.py file (with an `ENTRY`) in the
folders of $MCVAL_INTEGRATOR_PATH (os.pathsep-separated), so a test can add one without editing the harness.
"""
from __future__ import annotations

import importlib
import os
import pkgutil
from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cache
from pathlib import Path

from harness.integrators.entry import IntegratorEntry
from harness.plugin_files import plugin_objects

PATH_ENV = "MCVAL_INTEGRATOR_PATH"
_PACKAGE = "harness.integrators"
_NOT_ENTRIES = {"entry", "listing", "registry"}  # the machinery, not integrators


def _checked(entry: object, source: str) -> IntegratorEntry:
    if not isinstance(entry, IntegratorEntry):
        raise ValueError(f"{source}: ENTRY is a {type(entry).__name__}, expected an IntegratorEntry "
                         "(harness.integrators.entry)")
    return replace(entry, source=source)


def _package_entries() -> list[IntegratorEntry]:
    package = importlib.import_module(_PACKAGE)
    found = []
    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda m: m.name):
        if info.name in _NOT_ENTRIES or info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{_PACKAGE}.{info.name}")
        source = str(Path(module.__file__).relative_to(Path(package.__path__[0]).parents[1]))
        if not hasattr(module, "ENTRY"):
            raise ValueError(f"{source}: no ENTRY (each module of {_PACKAGE} but entry, listing and registry is one "
                             "integrator's entry)")
        found.append(_checked(module.ENTRY, source))
    return found


def _shown(path: Path) -> str:
    """The path as the user would type it: relative to the current folder when inside it."""
    try:
        return str(path.resolve().relative_to(Path.cwd()))
    except ValueError:
        return str(path)


@cache
def _discover(extra: str) -> dict[str, IntegratorEntry]:
    entries: dict[str, IntegratorEntry] = {}
    files = [_checked(entry, _shown(path)) for path, entry in plugin_objects(extra, "ENTRY", PATH_ENV)]
    for entry in _package_entries() + files:
        if entry.name in entries:
            raise ValueError(f"{entry.source}: integrator {entry.name!r} already has an entry in "
                             f"{entries[entry.name].source}")
        entries[entry.name] = entry
    return entries


def entries() -> dict[str, IntegratorEntry]:
    """Every entry found, by name: this package's, then those of $MCVAL_INTEGRATOR_PATH."""
    return _discover(os.environ.get(PATH_ENV, ""))


def entry(name: str) -> IntegratorEntry:
    found = entries()
    if name not in found:
        raise ValueError(f"unknown integrator {name!r}: the harness has entries for {', '.join(found)}")
    return found[name]


@dataclass(frozen=True)
class Matched:
    """The tested engine's integrators with their entries, and those the harness has no entry for."""

    entries: tuple[IntegratorEntry, ...]
    without_entry: tuple[str, ...]


def match(integrators: Sequence[str]) -> Matched:
    """The tested engine's `integrators` (Engine.integrators, in its order), each with its entry; an entry for an
    integrator the engine lacks is an error naming the entry's file."""
    found = entries()
    orphans = [e for name, e in found.items() if name not in integrators]
    if orphans:
        raise ValueError("; ".join(f"{e.source}: entry for integrator {e.name!r}, which the tested engine does not "
                                   f"render (its integrators: {', '.join(integrators)})" for e in orphans))
    return Matched(tuple(found[n] for n in integrators if n in found),
                   tuple(n for n in integrators if n not in found))
