"""Replays what must never crash: every scene of scenes/ with every integrator, and the fuzz corpus.

    .venv/bin/python tests/fuzz/replay.py --render build-sanitize/render

A corpus case is a folder of tests/fuzz/corpus/ holding scene.xml (and the mesh
files it names), `integrator` (the integrator to run), and `expect`: `image`, or
`error: <fragment>` for an error message that must contain the fragment. Each runs
in a scratch copy beside a FIFO, a folder, mesh.obj and mesh.ply, as the fuzzer's
variants do. The shipped scenes must give a finite image (or the refusal their
integrator's entry foresees). Exits 1 on any finding
or unmet expectation; `make sanitize` runs it with the ASan/UBSan build.
"""
from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_scenes import ROOT, add_special_files  # noqa: E402
from outcome import judge  # noqa: E402

sys.path.insert(0, str(ROOT))
from harness.integrators import entry  # noqa: E402
from tests.helpers.registered_integrators import PRODUCT  # noqa: E402

CORPUS = Path(__file__).resolve().parent / "corpus"


def _expected(scene: Path, integrator: str) -> str:
    """An image, or the refusal the integrator's entry foresees where the renderer refuses it too (simple on a
    plane lit by an area light). ao in the furnace is not applicable to the harness, but the renderer renders
    it: black."""
    why = entry(integrator).not_applicable(scene)
    return f"error: {why}" if why == "no point light" else "image"


def shipped_cases() -> list[tuple[str, Path, str, str]]:
    """(name, scene folder, integrator, expectation) for every scene of scenes/ and every integrator."""
    return [(f"{p.stem}:{i}", p, i, _expected(p, i)) for p in sorted((ROOT / "scenes").glob("*.xml")) for i in PRODUCT]


def corpus_cases(corpus: Path = CORPUS) -> list[tuple[str, Path, str, str]]:
    return [(d.name, d / "scene.xml", (d / "integrator").read_text().strip(), (d / "expect").read_text().strip())
            for d in sorted(corpus.iterdir()) if (d / "scene.xml").is_file()]


def replay(render: Path, name: str, scene: Path, integrator: str, expect: str, timeout: float) -> str | None:
    """None if the case met its expectation, else what went wrong."""
    with tempfile.TemporaryDirectory(prefix="mcval-replay-") as tmp:
        folder = Path(tmp) / "case"
        if scene.parent == ROOT / "scenes":  # a shipped scene: its meshes, by link
            folder.mkdir()
            (folder / "meshes").symlink_to(ROOT / "scenes/meshes")
            shutil.copy(scene, folder / "scene.xml")
        else:
            shutil.copytree(scene.parent, folder, symlinks=True)
            add_special_files(folder)
        outcome, detail = judge(render, folder / "scene.xml", integrator, timeout)
    kind, _, fragment = expect.partition(":")
    if outcome != kind or fragment.strip() not in detail:
        return f"{name} ({integrator}): expected {expect!r}, got {outcome}: {detail}"
    return None


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--render", type=Path, default=ROOT / "build/render", help="the render binary (default build/render)")
    p.add_argument("--timeout", type=float, default=300.0, help="seconds before a render counts as a hang (300)")
    p.add_argument("--corpus-only", action="store_true", help="skip the shipped scenes")
    args = p.parse_args(argv)
    cases = ([] if args.corpus_only else shipped_cases()) + corpus_cases()
    failures = []
    for n, (name, scene, integrator, expect) in enumerate(cases, 1):
        problem = replay(args.render.resolve(), name, scene, integrator, expect, args.timeout)
        print(f"[{n}/{len(cases)}] {name}: {'ok' if problem is None else 'FAIL'}", file=sys.stderr)
        if problem:
            failures.append(problem)
    for f in failures:
        print(f"FAIL {f}")
    print(f"{len(cases) - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
