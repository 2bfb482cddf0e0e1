"""Scene files given with --scene (files, or folders searched with their subfolders): each is copied, prepared,
into the run's output folder and rendered from there, so nothing is ever written beside it.

The copy differs from the file only in what every case of the suite sets (harness/images/scene_copy.py): its
<include>s inlined, its <path>s followed and file names made absolute (harness/engines/scene_paths.py), the
film's size as the `res` parameter of the resolution the run asks for (the suite's, --resolution, or a
reference image's width; the aspect kept), a camera for a file without one. A file in Nori's dialect is first
translated into Mitsuba 3's (harness/engines/nori). What cannot be prepared is the scene's `problem`: the file
is kept as it is, and its cases fail with that one line.
"""
from __future__ import annotations

import hashlib
import traceback
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from harness.engines.registry import scene_bounds
from harness.engines.nori.lined_xml import SceneXmlError, parse_lined
from harness.engines.nori.to_mitsuba import is_nori, nori_to_mitsuba
from harness.engines.scene_paths import SceneFileError
from harness.foreign_text import one_line
from harness.images.scene_copy import Prepared, prepare_mitsuba_file


@dataclass(frozen=True)
class UserScene:
    name: str        # the file's stem (scene_names): the scene's name in reports and in --only
    source: Path     # the file as given
    prepared: Path   # the copy that is rendered
    problem: str = ""  # why the file cannot be rendered at all (a Nori file without a translation), or ""
    notes: tuple[str, ...] = ()  # what its translation left out (only the file's own integrator would use it)
    dialect: str = "mitsuba"  # "nori" for a file in Nori's dialect
    #: Per line of the copy, the line of the file as given it came from (0: none; empty: not known).
    source_lines: tuple[int, ...] = ()
    traceback: str = ""  # where an unforeseen error in preparing the copy arose, for the run's log


def _scene_files_under(folder: Path, skip: tuple[Path, ...]) -> list[Path]:
    """The *.xml files under `folder` and its subfolders, hidden files and folders and `skip` left out."""
    found = []
    for path in sorted(folder.iterdir()):
        if path.name.startswith(".") or any(path.resolve() == s.resolve() for s in skip):
            continue
        if path.is_dir():
            found += _scene_files_under(path, skip)
        elif path.suffix == ".xml" and path.is_file():
            found.append(path)
    return found


def scene_files(paths: list[Path], skip: tuple[Path, ...] = ()) -> list[Path]:
    """Every scene file `paths` name: files as they are, folders as the *.xml files in them and their
    subfolders (not hidden ones, nor `skip`: the run's own output folder). ValueError naming a path that is
    neither or a folder without scene files."""
    found: list[Path] = []
    for path in paths:
        if path.is_dir():
            files = _scene_files_under(path, skip)
            if not files:
                raise ValueError(f"--scene {path}: a folder without .xml scene files")
            found += files
        elif path.is_file():
            found.append(path)
        else:
            raise ValueError(f"--scene {path}: no such file or folder")
    unique: dict[Path, Path] = {}
    for path in found:
        unique.setdefault(path.resolve(), path)
    return list(unique.values())


def scene_names(files: list[Path]) -> list[str]:
    """Each file's scene name: its stem, or where stems are shared (scene.xml in every folder of a corpus), the
    stem after as many of its folders as tell it apart ("kitchen-scene"). ValueError where none do."""
    names = []
    for path in files:
        for k in range(len(path.parts)):
            name = "-".join([*path.parts[-1 - k:-1], path.stem])
            if sum("-".join([*p.parts[-1 - k:-1], p.stem]) == name for p in files) == 1:
                break
        else:
            raise ValueError(f"--scene: two scenes are called {path.stem} and nothing tells {path} apart")
        names.append(name)
    return names


def _written(root: ET.Element) -> str:
    """The prepared copy's text, one element a line."""
    ET.indent(root)
    return ET.tostring(root, encoding="unicode")


def _prepared(path: Path, resolution: int, notes: list[str]) -> Prepared:
    """The file as the suite renders it (see the module docstring). SceneXmlError (NoriSceneError for a Nori
    file without a translation) naming the file and line of what cannot be prepared; what a Nori file's
    translation leaves out is a line in `notes`."""
    text = path.read_text(errors="replace")
    if not _is_nori_text(text):
        return prepare_mitsuba_file(text, path, resolution, scene_bounds, notes=notes)
    # Its translation's lines are not the file's: its copy keeps no map.
    translated = _written(nori_to_mitsuba(text, path, notes))
    return Prepared(prepare_mitsuba_file(translated, path, resolution, scene_bounds, lines=False, notes=notes).text)


def _is_nori_text(text: str) -> bool:
    try:
        return is_nori(parse_lined(text, Path("-")).root)
    except SceneXmlError:
        return False


def _prepare_one(path: Path, name: str, cache: Path, resolution: int) -> UserScene:
    """One scene file prepared; what cannot be prepared is the scene's problem (its cases fail with it)."""
    problem, notes, trace = "", [], ""
    dialect = "nori" if _is_nori_text(path.read_text(errors="replace")) else "mitsuba"
    try:
        prepared = _prepared(path, resolution, notes)
    except (SceneXmlError, SceneFileError) as e:
        prepared, problem = Prepared(path.read_text(errors="replace")), one_line(str(e))
    except OSError as e:  # a file the scene names that cannot be read (a folder, a name too long)
        prepared = Prepared(path.read_text(errors="replace"))
        problem = one_line(f"{path}: cannot read {e.filename or 'a file it names'}: {e.strerror or e}")
    except Exception as e:  # an input nobody foresaw costs its scene, not the run
        prepared = Prepared(path.read_text(errors="replace"))
        problem = one_line(f"{path}: its copy could not be prepared: {type(e).__name__}: {e}")
        trace = traceback.format_exc()
    digest = hashlib.sha256(f"{path.resolve()}\0{prepared.text}".encode()).hexdigest()[:16]
    copy = cache / digest / f"{name}.xml"
    if not copy.exists():
        copy.parent.mkdir(parents=True, exist_ok=True)
        tmp = copy.with_suffix(".tmp")
        tmp.write_text(prepared.text)
        tmp.replace(copy)
    return UserScene(name, path, copy, problem, tuple(notes), dialect, tuple(prepared.source_lines), trace)


def prepare_scenes(paths: list[Path], cache: Path, resolution: int, skip: tuple[Path, ...] = ()) -> list[UserScene]:
    """The scenes `paths` name (folders searched as scene_files does, `skip` left out), each prepared into
    cache/<digest>/<name>.xml (written once per content). ValueError for a file that cannot be read."""
    scenes = []
    files = scene_files(paths, skip)
    for path, name in zip(files, scene_names(files)):
        try:
            scenes.append(_prepare_one(path, name, cache, resolution))
        except OSError as e:
            raise ValueError(f"--scene {path}: cannot read it ({e.strerror or e})") from None
    return scenes
