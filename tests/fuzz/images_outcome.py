"""One `python -m harness images --scene ...` run over a batch of scene files, judged: the verdict of
fuzz_images.py. A refused scene is right (its cases fail with a reason, rc 1); these are findings:

  signal       the run was killed by a signal
  exit-status  any exit status but 0, 1 and 3 (2 is an error that stopped the whole run)
  hang         no exit within the time limit in CPU seconds, no CPU used for 10 s (blocked), or four times
               the limit in wall seconds (then SIGKILL: Mitsuba's loader ignores SIGTERM)
  memory       the run's processes held more than the memory limit (then SIGKILL)
  traceback    Python exception text in the output or in any string of results.json: "Traceback", "maximum
               recursion depth", or a built-in exception's name followed by ':' (IndexError: ...)
  exception-text  any other exception class's name and a colon: the names the harness prefixes to load errors
               it passes on (RuntimeError:, ValueError:, OSError: and its kin, its own SceneFileError:): the
               user reads a Python class name where their file's line belongs
  junit        junit.xml is not well-formed XML
  no-results   exit 0, 1 or 3 without results.json

Findings in one case's strings (results.json) or on an output line that names a scene belong to that scene;
the others belong to the whole run (fuzz_images.py bisects the batch to find the scene).
"""
from __future__ import annotations

import builtins
import json
import os
import re
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import psutil

ROOT = Path(__file__).resolve().parents[2]
FINDINGS = ("signal", "exit-status", "hang", "memory", "traceback", "exception-text", "junit", "no-results")
#: Exception names that wrap a load error's own message (Mitsuba's parser, a file the harness cannot read).
PASSED_ON = ("RuntimeError", "ValueError", "OSError", "FileNotFoundError", "IsADirectoryError", "NotADirectoryError",
             "PermissionError", "UnicodeDecodeError")
#: Python's own exceptions: a bug's text (IndexError: ...), but for those the harness passes load errors in.
BUILTIN_NAMES = sorted(n for n, v in vars(builtins).items() if isinstance(v, type) and issubclass(v, BaseException)
                       and n.endswith(("Error", "Exception")) and n not in PASSED_ON)
TRACEBACK_RE = re.compile(r"Traceback \(most recent call last\)|maximum recursion depth|\b(?:"
                          + "|".join(BUILTIN_NAMES) + r"):")
#: Any exception class's name and a colon (RuntimeError:, the harness's own SceneFileError:, NoriSceneError:).
CLASS_NAME_RE = re.compile(r"\b[A-Z]\w*(?:Error|Exception):")
#: Seconds our renderer and Mitsuba may take per render before the harness itself ends it (its own time limits,
#: MCVAL_RENDER_TIMEOUT and MCVAL_MITSUBA_TIMEOUT): a render that hangs then costs its case, which is the
#: behaviour under test; the campaign's hang verdict is for a harness that does not end it.
RENDER_TIMEOUT = "10"


@dataclass
class Finding:
    outcome: str
    detail: str
    scene: str | None = None  # the scene it belongs to, None: the whole run


@dataclass
class BatchRun:
    rc: int | None
    seconds: float
    output: str
    findings: list[Finding] = field(default_factory=list)


def images_command(scenes: list[Path], out: Path, resolution: int, seed: int) -> list[str]:
    command = [sys.executable, "-m", "harness", "images", "--resolution", str(resolution), "--seed", str(seed),
               "--out", str(out)]
    for scene in scenes:
        command += ["--scene", str(scene)]
    return command


#: A run is hung when its processes have used the time limit in CPU seconds (a machine shared with other work
#: stretches the wall clock, not the CPU time), when they have used next to no CPU for IDLE_SECONDS (a wait
#: on a FIFO or a lock), or after WALL_FACTOR times the limit in wall seconds.
WALL_FACTOR = 4
IDLE_SECONDS, IDLE_CPU = 10.0, 0.05


def _tree_usage(proc: psutil.Process, cpu_by_pid: dict[int, float]) -> tuple[int, float]:
    """(resident bytes of a process and its live children, CPU seconds of all it has run): `cpu_by_pid` keeps
    the last CPU time seen of each process, so that a child's seconds still count once it has exited."""
    rss = 0
    for p in [proc, *proc.children(recursive=True)]:
        try:
            rss += p.memory_info().rss
            times = p.cpu_times()
            cpu_by_pid[p.pid] = times.user + times.system
        except psutil.Error:
            pass
    return rss, sum(cpu_by_pid.values())


def run_images(scenes: list[Path], out: Path, resolution: int, seed: int, timeout: float,
               memory_limit: int) -> tuple[int | None, str, str, float]:
    """(exit status or None if killed for a hang or memory, why it was killed, the output, seconds). `timeout`
    is in CPU seconds of the run's processes (see WALL_FACTOR)."""
    start = time.perf_counter()
    log = out.with_suffix(".log")
    out.parent.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "MCVAL_RENDER_TIMEOUT": RENDER_TIMEOUT,
           "MCVAL_MITSUBA_TIMEOUT": RENDER_TIMEOUT, "COLUMNS": "200", "PYTHONUNBUFFERED": "1"}
    with open(log, "wb") as sink:
        proc = subprocess.Popen(images_command(scenes, out, resolution, seed), cwd=ROOT, stdout=sink,
                                stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=env, start_new_session=True)
        watched, killed, samples, cpu_by_pid = psutil.Process(proc.pid), "", [], {}
        while proc.poll() is None:
            rss, cpu = _tree_usage(watched, cpu_by_pid)
            wall = time.perf_counter() - start
            samples.append((wall, cpu))
            idle = [c for w, c in samples if w >= wall - IDLE_SECONDS]
            if cpu > timeout or wall > WALL_FACTOR * timeout:
                killed = f"hang: no exit after {cpu:.0f} CPU seconds, {wall:.0f} s"
            elif wall > IDLE_SECONDS and cpu - idle[0] < IDLE_CPU:
                killed = f"hang: no CPU used for {IDLE_SECONDS:.0f} s (blocked), after {wall:.0f} s"
            elif rss > memory_limit:
                killed = f"memory: more than {memory_limit >> 20} MiB"
            if killed:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                break
            time.sleep(0.2)
    output = log.read_bytes().decode(errors="replace")
    return (None if killed else proc.returncode), killed, output, time.perf_counter() - start


def _strings(value) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, dict):
        return [s for v in value.values() for s in _strings(v)]
    if isinstance(value, list):
        return [s for v in value for s in _strings(v)]
    return []


def _exception_text(text: str) -> tuple[str, str] | None:
    """(outcome, the line) of Python exception text in `text`: "traceback" for a traceback or a built-in
    exception's text, "exception-text" for a class name before a message passed on; or None."""
    m = TRACEBACK_RE.search(text) or CLASS_NAME_RE.search(text)
    if m is None:
        return None
    line_start = text.rfind("\n", 0, m.start()) + 1
    line_end = text.find("\n", m.end())
    line = text[line_start: line_end if line_end >= 0 else None].strip()[:300]
    return ("traceback" if m.re is TRACEBACK_RE else "exception-text"), line


def judge_run(rc: int | None, killed: str, output: str, out: Path, names: list[str]) -> list[Finding]:
    """The findings of one run whose run folder is under `out` and whose scenes are called `names`."""
    if killed:
        outcome, detail = killed.split(": ", 1)
        return [Finding(outcome, detail)]
    findings = []
    last = next((ln for ln in reversed(output.splitlines()) if ln.strip()), "")[:300]
    if rc is not None and rc < 0:
        findings.append(Finding("signal", f"{signal.Signals(-rc).name}; last line: {last}"))
    elif rc not in (0, 1, 3):
        findings.append(Finding("exit-status", f"exit {rc}: {last}"))
    name_re = re.compile(r"\b(" + "|".join(map(re.escape, names)) + r")\b") if names else None
    for line in output.splitlines():
        found = _exception_text(line)
        if found:
            m = name_re.search(line) if name_re else None
            findings.append(Finding(*found, m.group(1) if m else None))
    results = sorted(out.glob("*/results.json"))
    if rc in (0, 1, 3) and not results:
        findings.append(Finding("no-results", f"exit {rc} without results.json"))
    for path in results:
        try:
            data = json.loads(path.read_text())
        except ValueError as e:
            findings.append(Finding("no-results", f"results.json unreadable: {e}"))
            continue
        cases = data.get("images") or []
        for case in cases:
            for s in _strings(case):
                found = _exception_text(s)
                if found:
                    findings.append(Finding(*found, case.get("scene")))
        for s in _strings({k: v for k, v in data.items() if k != "images"}):
            found = _exception_text(s)
            if found:
                findings.append(Finding(*found))
    for path in sorted(out.glob("*/junit.xml")):
        try:
            ET.parse(path)
        except ET.ParseError as e:
            findings.append(Finding("junit", f"junit.xml: {e}"))
    return _unique(findings)


def _unique(findings: list[Finding]) -> list[Finding]:
    seen, kept = set(), []
    for f in findings:
        key = (f.outcome, f.scene, re.sub(r"\d+", "N", f.detail))
        if key not in seen:
            seen.add(key)
            kept.append(f)
    return kept


def last_named(output: str, names: list[str]) -> str | None:
    """The scene the output names last (the case running when a run died or hung), or None."""
    found = re.findall(r"\b(" + "|".join(map(re.escape, names)) + r")\b", output) if names else []
    return found[-1] if found else None


def run_batch(scenes: list[Path], out: Path, resolution: int, seed: int, timeout: float,
              memory_limit: int) -> BatchRun:
    rc, killed, output, seconds = run_images(scenes, out, resolution, seed, timeout, memory_limit)
    return BatchRun(rc, seconds, output, judge_run(rc, killed, output, out, [p.stem for p in scenes]))
