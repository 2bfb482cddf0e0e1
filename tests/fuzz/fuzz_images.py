"""A seeded fuzz campaign of `python -m harness images --scene`: the harness, Mitsuba and our renderer together.

    .venv/bin/python tests/fuzz/fuzz_images.py --runs 2000 --seed 1

Each variant is a scene of scenes/, scenes/real/, tests/renderer/scenes/ or tests/fuzz/corpus/ (or one of
fuzz_scenes.py's OBJ, serialized and a Nori-dialect scene) with either mutations aimed at the harness
(mutate_harness.py: malformed <default>s, huge names and values, deep nesting, no sensor or film, odd samplers,
crop windows, bad mesh indices, includes, 0.5 names, binary garbage) or the renderer's (mutate.py). Variants
run in batches, many `--scene`s to one process so that Mitsuba loads once, at a tiny --resolution, and each
batch is judged by images_outcome.py: a signal, an exit status other than 0, 1 and 3, a hang, a run past the
memory limit, Python exception text, a junit.xml that is not well-formed or a missing results.json is a
finding. A batch whose whole run breaks is bisected to the variant that breaks it. Each finding is saved
under --save (default tests/fuzz/findings/, git-ignored) as a folder with the scene, the files it names and
the command that reproduces it (at most --keep folders per kind of finding), and the driver exits 1.
"""
from __future__ import annotations

import argparse
import json
import os
import random
import re
import shutil
import sys
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_scenes import FILENAME_RE, Seed, add_special_files, load_seeds, make_variant  # noqa: E402
from images_outcome import FINDINGS, Finding, images_command, last_named, run_batch  # noqa: E402
from mutate_harness import mutate_for_harness  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
#: The --resolution of a batch: tiny, so that 2,000 variants take minutes; 4 is below SSIM's 7-pixel window.
RESOLUTIONS = (8, 8, 8, 16, 4)
NORI_MESH = b"v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n"
NORI_SCENE = b"""<scene>
    <integrator type="normals"/>
    <camera type="perspective">
        <transform name="toWorld"><lookat target="0, 0, 0" origin="0, 0, 4" up="0, 1, 0"/></transform>
        <float name="fov" value="40"/>
        <integer name="width" value="64"/><integer name="height" value="48"/>
    </camera>
    <sampler type="independent"><integer name="sampleCount" value="4"/></sampler>
    <mesh type="obj"><string name="filename" value="quad.obj"/>
        <bsdf type="diffuse"><color name="albedo" value="0.5, 0.5, 0.5"/></bsdf></mesh>
    <emitter type="point"><point name="position" value="0, 0, 3"/><color name="power" value="50, 50, 50"/></emitter>
</scene>
"""


def harness_seeds() -> list[Seed]:
    """fuzz_scenes.py's seeds, the suite's real scenes, the fuzz corpus's cases and a Nori-dialect scene."""
    seeds = load_seeds()
    paths = sorted((ROOT / "scenes" / "real").glob("*.xml")) + sorted((ROOT / "tests/fuzz/corpus").glob("*/scene.xml"))
    for path in paths:
        xml = path.read_bytes()
        names = (m.decode(errors="replace") for m in FILENAME_RE.findall(xml))
        meshes = {m: path.parent / m for m in names if len(m) < 255 and (path.parent / m).is_file()}
        name = path.stem if path.parent.name == "real" else "corpus-" + path.parent.name
        seeds.append(Seed(name, xml, meshes, 0.3 if name.startswith("corpus") else 1.0))
    seeds.append(Seed("nori_quad", NORI_SCENE, {"quad.obj": NORI_MESH}, 1.5))
    return seeds


@dataclass
class Variant:
    index: int
    seed: str
    mutation: str
    scene: Path  # <work>/v<index>/v<index>.xml: the stem names the scene's cases


def make_harness_variant(index: int, campaign_seed: int, seeds: list[Seed], work: Path) -> Variant:
    """Variant `index`: a third with the renderer's mutations (fuzz_scenes.make_variant), the rest with the
    harness's (mutate_harness.py) on an unchanged seed scene."""
    rng = random.Random(f"images:{campaign_seed}:{index}")
    folder = work / f"v{index}"
    if rng.random() < 0.33:
        v = make_variant(index, campaign_seed, seeds, work)
        scene = folder / f"v{index}.xml"
        (folder / "scene.xml").rename(scene)
        return Variant(index, v.seed, v.mutation, scene)
    seed = rng.choices(seeds, weights=[s.weight for s in seeds])[0]
    shutil.rmtree(folder, ignore_errors=True)
    (folder / "meshes").mkdir(parents=True)
    add_special_files(folder)
    for name, source in seed.meshes.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if not path.exists():
            path.write_bytes(source) if isinstance(source, bytes) else path.symlink_to(source.resolve())
    xml, mutation = mutate_for_harness(rng, seed.xml, folder)
    scene = folder / f"v{index}.xml"
    scene.write_bytes(xml)
    return Variant(index, seed.name, mutation, scene)


def save_finding(v: Variant, finding: Finding, resolution: int, seed: int, save: Path) -> Path:
    """Copy the variant (links resolved, FIFO and DIR left out) into save/<outcome>-<index>/ with a README."""
    dest = save / f"{finding.outcome}-{v.index}"
    shutil.rmtree(dest, ignore_errors=True)
    shutil.copytree(v.scene.parent, dest, ignore=shutil.ignore_patterns("FIFO", "DIR"))
    command = " ".join(images_command([dest / v.scene.name], Path("/tmp/fuzz-images-out"), resolution, seed))
    (dest / "README.txt").write_text(
        f"{finding.outcome}: {finding.detail}\nseed scene {v.seed}, mutation {v.mutation}\n"
        f"reproduce from the repository's root (first `mkfifo FIFO; mkdir DIR` here if the scene names them):\n"
        f"{command.replace(sys.executable, '.venv/bin/python')}\n")
    return dest


def kind_of(detail: str) -> str:
    """A finding's detail without its variant, numbers and paths, cut after the exception's first words: the
    findings of one cause share it."""
    detail = re.sub(r"^v\d+:\w+: ", "", detail)
    detail = re.sub(r"(/[^\s:\"']+)+", "PATH", detail)
    detail = re.sub(r"\d+", "N", detail)
    m = re.search(r"\w+(Error|Exception):|Traceback|maximum recursion", detail)
    return detail[: (m.end() + 60) if m else 120]


class Campaign:
    def __init__(self, args: argparse.Namespace):
        self.args = args
        self.counts: Counter[str] = Counter()   # findings per outcome, one per variant and outcome
        self.kinds: Counter[tuple[str, str]] = Counter()  # per (outcome, detail with its numbers blanked)
        self.findings: list[dict] = []
        self.runs = 0
        self.run_seconds = 0.0

    def timeout(self, n: int) -> float:
        return self.args.timeout + self.args.per_variant_timeout * n

    def batch(self, variants: list[Variant], resolution: int, tag: str) -> list[tuple[Variant, Finding]]:
        """The findings of `variants` as one run, each with its variant; a run-level one bisected."""
        out = self.args.work / "runs" / tag
        shutil.rmtree(out, ignore_errors=True)
        run = run_batch([v.scene for v in variants], out, resolution, self.args.seed, self.timeout(len(variants)),
                        self.args.memory_limit << 20)
        self.runs += 1
        self.run_seconds += run.seconds
        by_name = {v.scene.stem: v for v in variants}
        found = [(by_name[f.scene], f) for f in run.findings if f.scene in by_name]
        whole = [f for f in run.findings if f.scene not in by_name]
        if whole and len(variants) == 1:
            found += [(variants[0], f) for f in whole]
        elif whole:
            # The scene the output named last first (the case that was running), alone; else halves.
            suspect = by_name.get(last_named(run.output, list(by_name)))
            first = [suspect] if suspect else variants[: len(variants) // 2]
            rest = [v for v in variants if v not in first]
            how = f"suspect {suspect.scene.stem}" if suspect else "halves"
            print(f"  splitting {tag} ({len(variants)} variants; {how}): {whole[0].outcome}: {whole[0].detail[:120]}",
                  file=sys.stderr, flush=True)
            parts = self.batch(first, resolution, tag + "a") + self.batch(rest, resolution, tag + "b")
            found += parts
            if not any(p[1].outcome == w.outcome for p in parts for w in whole):  # only the whole batch breaks
                found += [(variants[0], Finding(w.outcome, w.detail + f" (only with variants "
                                                f"{variants[0].index}-{variants[-1].index} together)"))
                          for w in whole]
        shutil.rmtree(out, ignore_errors=True)
        out.with_suffix(".log").unlink(missing_ok=True)
        return found

    def record(self, found: list[tuple[Variant, Finding]], resolution: int) -> None:
        seen = set()
        for v, f in found:
            if (v.index, f.outcome) in seen:
                continue
            seen.add((v.index, f.outcome))
            self.counts[f.outcome] += 1
            kind = (f.outcome, kind_of(f.detail))
            self.kinds[kind] += 1
            saved = save_finding(v, f, resolution, self.args.seed, self.args.save) \
                if self.kinds[kind] <= self.args.keep else None
            self.findings.append({"index": v.index, "outcome": f.outcome, "detail": f.detail, "seed_scene": v.seed,
                                  "mutation": v.mutation, "resolution": resolution,
                                  "saved": str(saved) if saved else None})
            print(f"  {f.outcome}: variant {v.index} ({v.seed}, {v.mutation}): {f.detail[:200]}"
                  + (f" -> {saved}" if saved else ""), file=sys.stderr, flush=True)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__.split("\n\n", 2)[2])
    p.add_argument("--runs", type=int, default=2000, help="variants to try (default 2000)")
    p.add_argument("--seed", type=int, default=1, help="campaign seed (default 1)")
    p.add_argument("--batch", type=int, default=20, help="variants per harness process (default 20)")
    p.add_argument("--timeout", type=float, default=20.0, help="CPU seconds a run may use, plus --per-variant-timeout "
                   "for each variant, before it counts as a hang (20; no CPU used for 10 s, or 4 times the limit in "
                   "wall seconds, is a hang too)")
    p.add_argument("--per-variant-timeout", type=float, default=1.5, help="(default 1.5; a variant takes 0.5 s)")
    p.add_argument("--memory-limit", type=int, default=6144, help="MiB a run's processes may hold (default 6144)")
    p.add_argument("--keep", type=int, default=2, help="reproducers saved per kind of finding (default 2)")
    p.add_argument("--work", type=Path, default=ROOT / ".fuzz" / "images", help="scratch folder (.fuzz/images)")
    p.add_argument("--save", type=Path, default=ROOT / "tests/fuzz/findings", help="where findings go")
    p.add_argument("--json", type=Path, help="write the counts and findings as JSON here")
    args = p.parse_args(argv)
    if not (ROOT / "build" / "render").exists() and not os.environ.get("MCVAL_RENDER"):
        print("error: build/render does not exist: build it first (make build)", file=sys.stderr)
        return 2
    seeds = harness_seeds()
    shutil.rmtree(args.work, ignore_errors=True)
    args.work.mkdir(parents=True)
    campaign = Campaign(args)
    start = time.perf_counter()
    mutations: Counter[str] = Counter()
    for first in range(0, args.runs, args.batch):
        indices = range(first, min(first + args.batch, args.runs))
        variants = [make_harness_variant(i, args.seed, seeds, args.work) for i in indices]
        mutations.update(m for v in variants for m in v.mutation.split("+"))
        resolution = random.Random(f"images:{args.seed}:batch:{first}").choice(RESOLUTIONS)
        campaign.record(campaign.batch(variants, resolution, f"b{first}"), resolution)
        for v in variants:
            shutil.rmtree(v.scene.parent, ignore_errors=True)
        done, elapsed = indices.stop, time.perf_counter() - start
        print(f"{done}/{args.runs} variants, {elapsed:.0f} s ({elapsed / done:.2f} s a variant), eta "
              f"{elapsed / done * (args.runs - done):.0f} s, {len(campaign.findings)} findings", file=sys.stderr,
              flush=True)
    seconds = time.perf_counter() - start
    print("| finding | variants |\n|---|---|")
    for outcome in FINDINGS:
        print(f"| {outcome} | {campaign.counts[outcome]} |")
    print("\n| finding | detail (numbers as N) | variants |\n|---|---|---|")
    for (outcome, detail), n in campaign.kinds.most_common():
        print(f"| {outcome} | {detail.replace('|', '/')} | {n} |")
    print(f"\n{args.runs} variants (seed {args.seed}) in {seconds:.0f} s, {campaign.runs} harness runs; "
          f"{len(campaign.findings)} findings{' saved under ' + str(args.save) if campaign.findings else ''}")
    if args.json:
        args.json.write_text(json.dumps({"runs": args.runs, "seed": args.seed, "seconds": round(seconds, 1),
                                         "harness_runs": campaign.runs, "counts": dict(campaign.counts),
                                         "mutations": dict(mutations), "findings": campaign.findings}, indent=2) + "\n")
    return 1 if campaign.findings else 0


if __name__ == "__main__":
    sys.exit(main())
