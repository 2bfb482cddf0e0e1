"""Scene files given with --scene (a file or a folder of them, anywhere, read-only is fine): each is copied,
prepared, into the run's output folder and rendered from there, so nothing is ever written beside it.

The copy differs from the file only in what every case of the suite sets: its <include>s inlined, its <path>s
followed and file names made absolute (its meshes are read where they are; harness/engines/scene_paths.py),
and the film's size as the `res` parameter, declared as a <default> of the resolution the run asks for (the
suite's, --resolution, or a reference image's width; the aspect kept), which every render of the copy keeps.
A file in Nori's dialect is first translated into Mitsuba 3's (harness/engines/nori); one that cannot be is
kept as it is, and its cases fail with the translation's one line.
"""
from __future__ import annotations

import hashlib
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from harness.engines.nori.lined_xml import NoriSceneError
from harness.engines.nori.to_mitsuba import is_nori, nori_to_mitsuba
from harness.engines.scene_paths import SceneFileError, absolute_paths, anchor_paths
from harness.engines.written_scene import film_size


@dataclass(frozen=True)
class UserScene:
    name: str        # the file's stem: the scene's name in reports and in --only
    source: Path     # the file as given
    prepared: Path   # the copy that is rendered
    problem: str = ""  # why the file cannot be rendered at all (a Nori file without a translation), or ""
    notes: tuple[str, ...] = ()  # what its translation left out (only the file's own integrator would use it)
    dialect: str = "mitsuba"  # "nori" for a file in Nori's dialect


def scene_files(paths: list[Path]) -> list[Path]:
    """Every scene file `paths` name: files as they are, folders as their *.xml files. ValueError naming a path
    that is neither, a folder without scene files, or two scenes of one name."""
    found: list[Path] = []
    for path in paths:
        if path.is_dir():
            files = sorted(p for p in path.glob("*.xml") if not p.name.startswith("."))
            if not files:
                raise ValueError(f"--scene {path}: a folder without .xml scene files")
            found += files
        elif path.is_file():
            found.append(path)
        else:
            raise ValueError(f"--scene {path}: no such file or folder")
    names: dict[str, Path] = {}
    for path in found:
        if path.stem in names and names[path.stem].resolve() != path.resolve():
            raise ValueError(f"--scene: two scenes are called {path.stem} ({names[path.stem]} and {path}): "
                             "give one of them")
        names[path.stem] = path
    return list(names.values())


def _fill_size_parameters(root: ET.Element, film: ET.Element) -> None:
    """A film width or height given as a $parameter takes its <default> (in place): the suite sets the size."""
    defaults = {e.get("name"): e.get("value") for e in root.iter("default")}
    for e in film:
        value = e.get("value", "")
        if e.get("name") in ("width", "height") and value.startswith("$") and value[1:] in defaults:
            e.set("value", defaults[value[1:]])


def _written(root: ET.Element) -> str:
    """The prepared copy's text, one element a line: an engine's error then names a line that means something
    in the copy (which the case's error names beside the file as given)."""
    ET.indent(root)
    return ET.tostring(root, encoding="unicode")


def _prepared_text(path: Path, resolution: int, notes: list[str] | None = None) -> str:
    """The file's text as the suite renders it (see the module docstring); unchanged if it is not XML, so
    that each engine reports the error as it would on the file itself. NoriSceneError for a Nori file that
    has no translation; what a Nori file's translation leaves out is a line in `notes`."""
    text = path.read_text(errors="replace")
    try:
        root = ET.fromstring(text)
    except ET.ParseError:
        return text
    if is_nori(root):
        root = nori_to_mitsuba(text, path, notes)
        text = _written(root)
    try:
        absolute_paths(root, path)
    except SceneFileError:  # a <path> or <include> that leads nowhere: each engine's case says where
        root = ET.fromstring(text)
        anchor_paths(root, path.resolve().parent)
        return _written(root)
    film = next(root.iter("film"), None)
    if film is not None:
        _fill_size_parameters(root, film)
        try:
            width, height = film_size(root)
        except ValueError:  # a size given as a $parameter: left as the file has it
            return _written(root)
        for e in [e for e in film if e.get("name") in ("width", "height")]:
            film.remove(e)
        ET.SubElement(film, "integer", name="width", value="$res")
        ET.SubElement(film, "integer", name="height",
                      value="$res" if width == height else str(max(1, round(resolution * height / width))))
        for e in [e for e in root if e.tag == "default" and e.get("name") == "res"]:
            root.remove(e)  # the file's own default would give another size
        root.insert(0, ET.Element("default", name="res", value=str(resolution)))
    return _written(root)


def _is_nori_file(path: Path) -> bool:
    try:
        return is_nori(ET.parse(path).getroot())
    except (ET.ParseError, OSError):
        return False


def prepare_scenes(paths: list[Path], cache: Path, resolution: int) -> list[UserScene]:
    """The scenes `paths` name, each prepared into cache/<digest>/<name>.xml (written once per content)."""
    scenes = []
    for path in scene_files(paths):
        problem, notes = "", []
        dialect = "nori" if _is_nori_file(path) else "mitsuba"
        try:
            text = _prepared_text(path, resolution, notes)
        except OSError as e:
            raise ValueError(f"--scene {path}: cannot read it ({e.strerror or e})") from None
        except NoriSceneError as e:
            text, problem = path.read_text(errors="replace"), str(e)
        digest = hashlib.sha256(f"{path.resolve()}\0{text}".encode()).hexdigest()[:16]
        prepared = cache / digest / f"{path.stem}.xml"
        if not prepared.exists():
            prepared.parent.mkdir(parents=True, exist_ok=True)
            tmp = prepared.with_suffix(".tmp")
            tmp.write_text(text)
            tmp.replace(prepared)
        scenes.append(UserScene(path.stem, path, prepared, problem, tuple(notes), dialect))
    return scenes
