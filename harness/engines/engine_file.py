"""Engine files: a TOML description of how to call a renderer that reads a scene file and writes an EXR
(docs/engines.md). Reading one checks everything that can be checked before a call, so a mistake in the file
is one line naming the file, the line where it can be found, and what was expected."""
from __future__ import annotations

import math
import os
import re
import shutil
import string
import tomllib
from dataclasses import dataclass
from pathlib import Path

#: The placeholders a command may hold, and the two it must.
PLACEHOLDERS = ("scene", "output", "spp", "seed", "integrator", "width", "height", "threads", "batches", "here")
REQUIRED_PLACEHOLDERS = ("scene", "output")
KEYS = ("name", "command", "version", "scene_format", "jobs", "timeout", "integrators", "other_estimators")


class EngineFileError(ValueError):
    """A mistake in an engine file, as one line: "FILE:LINE: what is wrong"."""


@dataclass(frozen=True)
class EngineFile:
    """One engine file, checked. `command` and `version` still hold their placeholders; `here` is the file's
    folder, which `{here}` stands for."""

    path: Path
    name: str
    command: tuple[str, ...]
    integrators: dict[str, str]
    version: tuple[str, ...] = ()
    scene_format: str = "mitsuba"
    jobs: int = 1
    timeout: float | None = None
    #: mcval's integrators for which the renderer draws an estimator of its own (the same expected image, other
    #: noise: a sphere light sampled by area, not by the cone it subtends). Only their images' means are judged.
    other_estimators: frozenset[str] = frozenset()

    @property
    def here(self) -> Path:
        return self.path.parent

    @property
    def renders_batches(self) -> bool:
        """Whether its command holds {batches}: one call renders several of a case's images."""
        return "batches" in _placeholders(self.command)


def looks_like_engine_file(name: str) -> bool:
    """Whether an --engine value names a file rather than a registered engine."""
    return name.endswith(".toml") or os.sep in name


def _line_of(text: str, key: str) -> int:
    """The line where `key` is first set (1 if it cannot be found): for messages only."""
    match = re.search(rf"^\s*\[?\s*{re.escape(key)}\s*[=\]]", text, re.MULTILINE)
    return text.count("\n", 0, match.start()) + 1 if match else 1


def _words(value: object) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(w, str) for w in value)


def _placeholders(words: tuple[str, ...]) -> set[str]:
    """The placeholders the words hold; ValueError naming the word when one has an unbalanced brace."""
    found = set()
    for w in words:
        try:
            found |= {field for _, field, _, _ in string.Formatter().parse(w) if field is not None}
        except ValueError as e:  # "{output" or "out}": what str.format would raise at the first call
            raise ValueError(f"{w!r} is not a word with placeholders ({e}; a literal brace is written {{{{ or }}}})") \
                from None
    return found


def _program(first: str, here: Path) -> str | None:
    """Why the command's first word cannot be run, or None if it can."""
    path = first.replace("{here}", str(here))
    if os.sep not in path:
        return None if shutil.which(path) else f"{path!r} is not a program on PATH"
    if Path(path).is_dir():
        return f"{path} is a folder, not a program"
    if not Path(path).is_file():
        return f"{path} does not exist"
    if not os.access(path, os.X_OK):
        return f"{path} is not executable (chmod +x)"
    return None


def read_engine_file(path: str | Path) -> EngineFile:
    """The engine file at `path`, checked; EngineFileError saying where and what otherwise."""
    path = Path(path).resolve()
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise EngineFileError(f"{path}: cannot read the engine file ({e.strerror or e})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        line = raw.count(b"\n", 0, e.start) + 1
        raise EngineFileError(f"{path}:{line}: not a TOML text file (byte {e.start} is not UTF-8; an engine file "
                              "is text: see docs/engines.md)") from None
    if "\0" in text:
        raise EngineFileError(f"{path}:{text.count(chr(10), 0, text.index(chr(0))) + 1}: not a TOML text file "
                              "(it holds NUL bytes; an engine file is text: see docs/engines.md)")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        # tomllib says where in its message: "... (at line 2, column 11)" or "(at end of document)".
        where = re.search(r"\(at line (\d+), column \d+\)", str(e))
        line = where.group(1) if where else text.count("\n") + (not text.endswith("\n"))
        reason = re.sub(r" \(at (line \d+, column \d+|end of document)\)", "", str(e))
        raise EngineFileError(f"{path}:{line}: not valid TOML: {reason}") from None

    def error(key: str, message: str) -> EngineFileError:
        return EngineFileError(f"{path}:{_line_of(text, key)}: {message}")

    for key in data:
        if key not in KEYS:
            raise error(key, f"unknown key {key!r} (an engine file has {', '.join(KEYS)})")
    for key in ("name", "command", "integrators"):
        if key not in data:
            raise EngineFileError(f"{path}:1: missing {key!r} (see docs/engines.md)")
    name = data["name"]
    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._+-]*", name):
        raise error("name", f"name must be a word of letters, digits and . _ + - (got {name!r})")
    command = data["command"]
    if not _words(command):
        raise error("command", "command must be a list of strings, the program first")
    command = tuple(command)
    try:
        found = _placeholders(command)
    except ValueError as e:
        raise error("command", f"command: {e}") from None
    unknown = sorted(found - set(PLACEHOLDERS))
    if unknown:
        raise error("command", f"unknown placeholder {{{unknown[0]}}} in command (placeholders: "
                               f"{', '.join('{' + p + '}' for p in PLACEHOLDERS)})")
    for needed in REQUIRED_PLACEHOLDERS:
        if needed not in found:
            raise error("command", f"command has no {{{needed}}}: the harness could not tell the renderer "
                                   f"{'which scene to render' if needed == 'scene' else 'where to write the EXR'}")
    problem = _program(command[0], path.parent)
    if problem:
        raise error("command", f"cannot run the command: {problem}")
    version = data.get("version", [])
    if version and not _words(version):
        raise error("version", "version must be a list of strings (a command printing the version)")
    from harness.engines.scene_writers import SCENE_WRITERS
    scene_format = data.get("scene_format", next(iter(SCENE_WRITERS)))
    if scene_format not in SCENE_WRITERS:
        raise error("scene_format", f"scene_format {scene_format!r} is not one of {', '.join(SCENE_WRITERS)}")
    jobs = data.get("jobs", 1)
    if not isinstance(jobs, int) or isinstance(jobs, bool) or jobs < 1:
        raise error("jobs", f"jobs must be a whole number of at least 1 (got {jobs!r})")
    timeout = data.get("timeout")
    # A NaN or infinite timeout would disable it (a hung renderer then hangs the run): finite and positive only.
    if timeout is not None and (isinstance(timeout, bool) or not isinstance(timeout, (int, float))
                                or not math.isfinite(timeout) or timeout <= 0):
        raise error("timeout", f"timeout must be a finite positive number of seconds (got {timeout!r})")
    integrators = data["integrators"]
    if not isinstance(integrators, dict) or not integrators:
        raise error("integrators", "[integrators] must map mcval's integrators to this renderer's names")
    from harness.integrators import entries
    known = entries()
    for integrator, theirs in integrators.items():
        if integrator in KEYS and integrator not in known:
            raise error(integrator, f"{integrator} is read as a line of [integrators]: write it above that table "
                                    "(TOML gives every key after a [table] line to the table)")
        if integrator not in known:
            raise error(integrator, f"integrators: {integrator!r} is not an integrator of mcval "
                                    f"(it has {', '.join(known)})")
        if not isinstance(theirs, str) or not theirs:
            raise error(integrator, f"integrators.{integrator} must be the renderer's name for it, a string")
    other = data.get("other_estimators", [])
    if not isinstance(other, list) or not all(isinstance(i, str) for i in other):
        raise error("other_estimators", "other_estimators must be a list of mcval's integrators (e.g. [\"direct\"])")
    for integrator in other:
        if integrator not in integrators:
            raise error("other_estimators", f"other_estimators: {integrator!r} is not in [integrators] (this "
                                            f"renderer maps {', '.join(integrators)})")
    return EngineFile(path, name, command, dict(integrators), tuple(version), scene_format, jobs,
                      None if timeout is None else float(timeout), frozenset(other))
