"""A scene file's other files, found as Mitsuba 3 finds them, so that its text can be handed on from anywhere.

Mitsuba resolves a relative file name against a list of folders: the scene's own, and before it every folder a
`<path value="...">` names (relative to the file that says it, else to those folders; each new one searched
first). `<include
filename="...">` inserts another scene file's elements where it stands. `absolute_paths` does the same once and
for all: the includes inlined, the `<path>`s used and removed, and every file name made absolute, so that
Mitsuba (loading from memory) and an engine file's renderer (reading a copy written elsewhere) see the scene as
Mitsuba would read the original.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

#: Properties holding a file name.
_FILE_PROPERTIES = ("filename",)
#: Includes deeper than this are a cycle or a mistake.
MAX_INCLUDE_DEPTH = 16


class SceneFileError(ValueError):
    """A <path> or <include> that cannot be followed; the message names the file and what is wrong."""


def _resolve(name: str, folders: list[Path]) -> Path | None:
    """The first folder / name that exists, as Mitsuba's FileResolver picks it; None if none does."""
    if Path(name).is_absolute():
        return Path(name) if Path(name).exists() else None
    return next(((f / name).resolve() for f in folders if (f / name).exists()), None)


def _expand(parent: ET.Element, file: Path, folders: list[Path], chain: tuple[Path, ...],
            lines: dict[int, int]) -> None:
    """<path> and <include> under `parent` (read from `file`) followed in document order, in place. `lines`:
    the line of each element read from the file first given, by id (the errors name it)."""
    index = 0
    while index < len(parent):
        e = parent[index]
        where = f"{file}:{lines[id(e)]}" if file == chain[0] and id(e) in lines else str(file)
        if e.tag == "path":
            value = e.get("value", "")
            folder = Path(value) if Path(value).is_absolute() else file.parent / value
            if "$" not in value and not folder.is_dir():  # Mitsuba then asks its resolver's folders
                found = _resolve(value, folders)
                folder = found if found is not None and found.is_dir() else folder
            if "$" in value or not folder.is_dir():
                raise SceneFileError(f"{where}: <path value=\"{value}\">: no such folder ({folder})")
            folders.insert(0, folder.resolve())
            del parent[index]
            continue
        if e.tag == "include":
            name = e.get("filename", "")
            found = _resolve(name, folders) if name and "$" not in name else None
            if found is None:
                missing = "no such file" if Path(name).is_absolute() else \
                    f"not found in {', '.join(str(f) for f in folders)}"
                raise SceneFileError(f"{where}: <include filename=\"{name}\">: {missing}")
            if not found.is_file():  # a named pipe would block the reader for ever, a device never end
                raise SceneFileError(f"{where}: <include filename=\"{name}\">: not a regular file ({found})")
            if found in chain or len(chain) >= MAX_INCLUDE_DEPTH:
                raise SceneFileError(f"{where}: <include filename=\"{name}\">: includes itself "
                                     f"({' -> '.join(p.name for p in (*chain, found))})")
            try:
                included = ET.parse(found).getroot()
            except ET.ParseError as err:
                raise SceneFileError(f"{found}: not an XML scene file ({err}), included by {file}") from None
            if included.tag != "scene":
                raise SceneFileError(f"{found}: an included file's root must be <scene>, not <{included.tag}>")
            _expand(included, found, folders, (*chain, found), lines)
            parent[index:index + 1] = list(included)
            index += len(included)
            continue
        if e.tag == "string" and e.get("name") in _FILE_PROPERTIES and e.get("value"):
            value = e.get("value")
            if "$" not in value and not Path(value).is_absolute():
                found = _resolve(value, folders)
                e.set("value", str(found if found is not None else (file.parent / value).resolve()))
        _expand(e, file, folders, chain, lines)
        index += 1


def absolute_paths(root: ET.Element, file: Path, lines: dict[int, int] | None = None) -> None:
    """`root` (the scene read from `file`) with its includes inlined, its <path>s followed and removed, and
    every relative file name made absolute (in place). SceneFileError for a <path> or <include> that leads
    nowhere, naming its line where `lines` (by element id, harness/engines/nori/lined_xml.py) gives it."""
    file = Path(file).resolve()
    _expand(root, file, [file.parent], (file,), lines or {})


def anchor_paths(root: ET.Element, folder: Path) -> None:
    """Only the relative <path> folders and <include> files under `root` made absolute against `folder` (in
    place): a copy written elsewhere then fails as the original does, naming the same files."""
    for e in root.iter():
        key = {"path": "value", "include": "filename"}.get(e.tag)
        value = e.get(key, "") if key else ""
        if value and "$" not in value and not Path(value).is_absolute():
            e.set(key, str((folder / value).resolve()))
