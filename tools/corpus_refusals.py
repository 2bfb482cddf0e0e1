"""How `images --scene` treats folders of other people's scene files: cases passed, failed, refused, and the
refusals whose reason holds Python exception text, grouped by reason with an example file each.

    .venv/bin/python tools/corpus_refusals.py /work/corpora/mitsuba-data /work/corpora/nori --resolution 16

Every *.xml under each folder (subfolders too) whose root element is <scene> is a scene (include fragments
count: they are files a user may give). Scenes run in chunks of --chunk files (unique names) through
`python -m harness images --scene ...` with the fuzz campaign's time and memory limits
(tests/fuzz/images_outcome.py); a chunk whose run breaks as a whole runs again one file at a time, and a file
whose own run breaks counts as "run lost" with why. A case is passed (PASS), failed (judged, not PASS: FAIL or
INCONCLUSIVE), refused (an error before any comparison: the case's `error`) or not applicable (the integrator
needs what the scene lacks). Reasons are grouped with the file's paths and numbers blanked.
"""
from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "fuzz"))
from images_outcome import _exception_text, judge_run, run_images  # noqa: E402

#: What ends a whole run (the rest of images_outcome's findings are a case's text).
RUN_BREAKS = ("signal", "exit-status", "hang", "memory", "junit", "no-results")
#: A case the run lists as not applicable (the integrator needs what the scene lacks): never in results.json.
NOT_APPLICABLE_RE = re.compile(r"^(\S+):\w+: not applicable", re.M)


def scene_files(folder: Path) -> list[Path]:
    """The *.xml files under `folder` whose root element is <scene>."""
    found = []
    for path in sorted(folder.rglob("*.xml")):
        try:
            root_tag = next(ET.iterparse(path, events=("start",)))[1].tag
        except (ET.ParseError, StopIteration, OSError, UnicodeDecodeError):
            root_tag = "scene"  # not well-formed: a scene file the harness must refuse well
        if root_tag == "scene":
            found.append(path)
    return found


def chunks(files: list[Path], size: int) -> list[list[Path]]:
    """Groups of at most `size` files, no two of one name (the harness refuses two scenes of one name)."""
    groups: list[list[Path]] = []
    for path in files:
        group = next((g for g in groups if len(g) < size and all(p.stem != path.stem for p in g)), None)
        if group is None:
            groups.append(group := [])
        group.append(path)
    return groups


def reason_key(reason: str, path: Path) -> str:
    """A refusal's reason without the file's own paths, numbers and the reproducing command."""
    reason = reason.split(": python -m harness")[0]
    reason = reason.replace(str(path.parent), "DIR").replace(path.stem, "NAME")
    reason = re.sub(r"(/[^\s:\"']+)+", "PATH", reason)
    return re.sub(r"\d+", "N", reason)[:200]


class Tally:
    def __init__(self) -> None:
        self.cases: Counter[str] = Counter()
        self.reasons: dict[str, list[Path]] = defaultdict(list)
        self.exception_reasons: Counter[str] = Counter()
        self.lost: list[tuple[Path, str]] = []
        self.files = 0

    def add_case(self, case: dict, path: Path) -> None:
        error, verdict = case.get("error"), case.get("verdict")
        if error:
            self.cases["refused"] += 1
            key = reason_key(error, path)
            self.reasons[key].append(path)
            if _exception_text(error):
                self.cases["refused with exception text"] += 1
                self.exception_reasons[key] += 1
        elif verdict == "PASS":
            self.cases["passed"] += 1
        elif verdict in ("FAIL", "INCONCLUSIVE"):
            self.cases["failed"] += 1
        else:
            self.cases[f"other ({verdict})"] += 1


def run_chunk(files: list[Path], out: Path, args: argparse.Namespace, tally: Tally, log) -> None:
    shutil.rmtree(out, ignore_errors=True)
    rc, killed, output, seconds = run_images(files, out, args.resolution, 0, args.timeout + args.per_file * len(files),
                                             args.memory_limit << 20)
    whole = [f for f in judge_run(rc, killed, output, out, [p.stem for p in files]) if f.outcome in RUN_BREAKS]
    results = sorted(out.glob("*/results.json"))
    if (whole or not results) and len(files) > 1:
        print(f"  run of {len(files)} files broke ({whole[0].outcome if whole else 'no results'}): one at a time",
              file=log, flush=True)
        for i, path in enumerate(files):
            run_chunk([path], out.with_name(f"{out.name}-{i}"), args, tally, log)
        return
    if whole or not results:
        why = f"{whole[0].outcome}: {whole[0].detail}" if whole else f"exit {rc} without results.json"
        tally.lost.append((files[0], why[:300]))
        print(f"  run lost: {files[0]}: {why[:200]}", file=log, flush=True)
        return
    by_name = {p.stem: p for p in files}
    tally.cases["not applicable"] += sum(m in by_name for m in NOT_APPLICABLE_RE.findall(output))
    data = json.loads(results[0].read_text())
    for case in data.get("images") or []:
        if case.get("scene") in by_name:
            tally.add_case(case, by_name[case["scene"]])
    shutil.rmtree(out, ignore_errors=True)


def report(corpora: dict[str, Tally], seconds: float, args: argparse.Namespace) -> str:
    kinds = ["passed", "failed", "refused", "refused with exception text", "not applicable"]
    lines = ["| corpus | files | " + " | ".join(kinds) + " | run lost |", "|---" * (len(kinds) + 3) + "|"]
    total = Tally()
    for name, t in corpora.items():
        lines.append(f"| {name} | {t.files} | " + " | ".join(str(t.cases[k]) for k in kinds) + f" | {len(t.lost)} |")
        total.cases.update(t.cases)
        total.lost += t.lost
        total.exception_reasons.update(t.exception_reasons)
        for k, v in t.reasons.items():
            total.reasons[k] += v
    lines.append(f"| all | {sum(t.files for t in corpora.values())} | "
                 + " | ".join(str(total.cases[k]) for k in kinds) + f" | {len(total.lost)} |")
    lines += ["", "| refusals | reason (paths, names and numbers blanked) | exception text | example |", "|---|---|---|---|"]
    for key, paths in sorted(total.reasons.items(), key=lambda kv: -len(kv[1]))[: args.top]:
        lines.append(f"| {len(paths)} | {key.replace('|', '/')} | {'yes' if key in total.exception_reasons else ''} "
                     f"| {paths[0]} |")
    for path, why in total.lost:
        lines.append(f"\nrun lost: {path}: {why}")
    lines.append(f"\n{seconds:.0f} s at --resolution {args.resolution}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__.split("\n\n", 2)[2])
    p.add_argument("folders", nargs="+", type=Path, help="folders of scene files (searched with their subfolders)")
    p.add_argument("--resolution", type=int, default=16, help="--resolution of the runs (default 16)")
    p.add_argument("--chunk", type=int, default=10, help="files per harness run (default 10)")
    p.add_argument("--timeout", type=float, default=60.0, help="seconds a run may take, plus --per-file a file (60)")
    p.add_argument("--per-file", type=float, default=300.0, help="(default 300: a file without a <film> renders "
                                                               "768 x 576 in Mitsuba, over a minute a case)")
    p.add_argument("--memory-limit", type=int, default=8192, help="MiB a run's processes may hold (default 8192)")
    p.add_argument("--top", type=int, default=25, help="reasons listed (default 25)")
    p.add_argument("--json", type=Path, help="write the counts, reasons and their files as JSON here")
    args = p.parse_args(argv)
    start = time.perf_counter()
    corpora: dict[str, Tally] = {}
    with tempfile.TemporaryDirectory(prefix="corpus-refusals-") as tmp:
        for folder in args.folders:
            tally = corpora[str(folder)] = Tally()
            files = scene_files(folder)
            tally.files = len(files)
            for i, group in enumerate(chunks(files, args.chunk)):
                print(f"{folder}: chunk {i + 1}, {len(group)} files, {time.perf_counter() - start:.0f} s",
                      file=sys.stderr, flush=True)
                run_chunk(group, Path(tmp) / f"{len(corpora)}-{i}", args, tally, sys.stderr)
    seconds = time.perf_counter() - start
    print(report(corpora, seconds, args))
    if args.json:
        args.json.write_text(json.dumps({
            "seconds": round(seconds, 1), "resolution": args.resolution,
            "corpora": {name: {"files": t.files, "cases": dict(t.cases), "lost": [[str(p), w] for p, w in t.lost],
                               "reasons": {k: [str(p) for p in v] for k, v in t.reasons.items()},
                               "exception_reasons": dict(t.exception_reasons)} for name, t in corpora.items()}},
            indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
