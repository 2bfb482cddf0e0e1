"""A seeded mutation fuzzer for the renderer: scene files and meshes in, one verdict per variant out.

    .venv/bin/python tests/fuzz/fuzz_scenes.py --runs 20000 --seed 1 --render build/render

Each variant is a scene of scenes/ (or a small OBJ scene made here) with one to
three mutations of its XML or its mesh (see mutate.py), rendered at 32x32 and 1
spp with one integrator, and judged by outcome.py: a finite image or a clear
`file:line` error is right; a signal, a hang (no exit within --timeout), an image
with NaN/Inf or negative pixels, an unclear error or a leftover temporary file is
a finding. Each finding is saved under --save (default tests/fuzz/crashes/)
as a folder with the scene, its meshes and the command that reproduces it, and the
driver exits 1. Why a mutation fuzzer rather than libFuzzer: it runs the real
`render` end to end (CLI, loader, meshes, Embree, film, EXR output), detects hangs
and bad images as well as crashes, and needs only gcc; a fixed seed makes every
campaign repeatable.
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
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path[:0] = [str(Path(__file__).resolve().parent), str(ROOT / "tests" / "helpers")]
from light_seeds import LIGHT_SEEDS  # noqa: E402
from mutate import mutate_bytes, mutate_obj, mutate_ply, mutate_xml  # noqa: E402
from outcome import FINDINGS, OUTCOMES, judge, render_command  # noqa: E402
from registered_integrators import PRODUCT  # noqa: E402

#: Every integrator the renderer registers; a seed whose file sets up `direct` is rendered with it more often.
INTEGRATORS = tuple(PRODUCT)
DIRECT_SEED_SHARE = 0.4
#: A small OBJ (a tetrahedron with normals and texture coordinates) and a scene that uses it.
OBJ_MESH = b"""# tetrahedron
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 0 1
vn 0 0 -1
vn 0 -1 0
vn -1 0 0
vn 0.577 0.577 0.577
f 1/1/1 3/3/1 2/2/1
f 1/1/2 2/2/2 4/3/2
f 1/1/3 4/3/3 3/2/3
f 2/1/4 3/2/4 4/3/4
"""
OBJ_SCENE = b"""<scene version="3.0.0">
    <default name="res" value="32"/>
    <integrator type="ao"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="3, 2, 4" target="0.3, 0.3, 0.3" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/>
            <rfilter type="gaussian"><float name="stddev" value="0.5"/></rfilter></film>
    </sensor>
    <shape type="obj"><string name="filename" value="mesh.obj"/>
        <transform name="to_world"><rotate y="1" angle="20"/><translate x="0.1"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.6, 0.5"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="5"/><rotate x="1" angle="-90"/></transform></shape>
    <emitter type="point"><point name="position" value="2, 3, 2"/><rgb name="intensity" value="10"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>
"""
#: A serialized mesh (Mitsuba's compressed format) under two instances of a shapegroup, one mirroring.
SERIALIZED_SCENE = b"""<scene version="3.0.0">
    <default name="res" value="32"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 2, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    </sensor>
    <shape type="shapegroup" id="group">
        <shape type="serialized"><string name="filename" value="mesh.serialized"/>
            <integer name="shape_index" value="1"/></shape>
        <shape type="sphere"><float name="radius" value="0.3"/><point name="center" value="0, 1, 0"/></shape>
    </shape>
    <shape type="instance"><ref id="group"/></shape>
    <shape type="instance"><ref id="group"/>
        <transform name="to_world"><scale value="-1, 1, 1"/><translate x="1.5"/></transform></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="5"/><rotate x="1" angle="-90"/></transform></shape>
    <emitter type="point"><point name="position" value="2, 3, 2"/><rgb name="intensity" value="10"/></emitter>
</scene>
"""
FILENAME_RE = re.compile(rb'name="filename"\s+value="([^"]*)"')
#: Scenes beside the suite's that hold what the suite's do not (disks, cylinders, an orthographic sensor, OBJ
#: meshes lit by an area emitter).
EXTRA_SEED_DIRS = (ROOT / "tests" / "renderer" / "scenes", ROOT / "scenes" / "real")


def _serialized_mesh() -> bytes:
    """Two shapes (version 4): a sphere with normals and a pyramid without."""
    import tempfile

    from serialized_files import pyramid, uv_sphere, write_serialized

    with tempfile.TemporaryDirectory() as tmp:
        return write_serialized(Path(tmp) / "m.serialized", [uv_sphere(), pyramid()]).read_bytes()


def _mutate_serialized(rng: random.Random, data: bytes) -> tuple[bytes, str]:
    return mutate_bytes(rng, data), "serialized bytes"


MESH_MUTATIONS = {".obj": mutate_obj, ".ply": mutate_ply, ".serialized": _mutate_serialized}


@dataclass
class Seed:
    """A scene to mutate: its XML and the mesh files it names (relative path -> bytes)."""

    name: str
    xml: bytes
    meshes: dict[str, Path | bytes]
    weight: float


def load_seeds() -> list[Seed]:
    seeds = []
    paths = sorted((ROOT / "scenes").glob("*.xml")) + [p for d in EXTRA_SEED_DIRS for p in sorted(d.glob("*.xml"))]
    for path in paths:
        xml = path.read_bytes()
        meshes = {m.decode(): path.parent / m.decode() for m in FILENAME_RE.findall(xml)}
        big = any(p.stat().st_size > 1 << 20 for p in meshes.values())
        seeds.append(Seed(path.stem, xml, meshes, 0.15 if big else 1.0))  # large meshes load slowly
    seeds.append(Seed("obj_tetrahedron", OBJ_SCENE, {"mesh.obj": OBJ_MESH}, 1.5))
    seeds.append(Seed("serialized_instances", SERIALIZED_SCENE, {"mesh.serialized": _serialized_mesh()}, 1.5))
    seeds += [Seed(name, xml, {"mesh.obj": OBJ_MESH}, 2.0) for name, xml in LIGHT_SEEDS]
    return seeds


def add_special_files(folder: Path) -> None:
    """What mutated file names point at: a FIFO, a folder, a small OBJ (unless a reproducer brings its own) and
    a PLY."""
    os.mkfifo(folder / "FIFO")
    (folder / "DIR").mkdir()
    if not (folder / "mesh.obj").exists():
        (folder / "mesh.obj").write_bytes(OBJ_MESH)
    (folder / "mesh.ply").symlink_to(ROOT / "scenes/meshes/sphere.ply")


@dataclass
class Variant:
    index: int
    seed: str
    integrator: str
    mutation: str
    folder: Path


def make_variant(index: int, campaign_seed: int, seeds: list[Seed], work: Path) -> Variant:
    """Write variant `index` of the campaign into its own folder under `work`."""
    rng = random.Random(f"{campaign_seed}:{index}")
    seed = rng.choices(seeds, weights=[s.weight for s in seeds])[0]
    integrator = rng.choice(INTEGRATORS)
    if b'<integrator type="direct"' in seed.xml and rng.random() < DIRECT_SEED_SHARE:
        integrator = "direct"  # so that the file's parameters of direct are read
    folder = work / f"v{index}"
    shutil.rmtree(folder, ignore_errors=True)
    (folder / "meshes").mkdir(parents=True)
    add_special_files(folder)
    xml, mutations = seed.xml, []
    mesh_names = list(seed.meshes)
    target = rng.random()
    if mesh_names and target < 0.4:
        name = rng.choice(mesh_names)
        source = seed.meshes[name]
        data = source if isinstance(source, bytes) else source.read_bytes()
        data, what = MESH_MUTATIONS[Path(name).suffix](rng, data)
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(data)
        mutations.append(what)
    if not mutations or target > 0.3:
        xml, what = mutate_xml(rng, xml)
        mutations.append(what)
    for name in mesh_names:  # the unmutated meshes, linked rather than copied
        path = folder / name
        if not path.exists():
            path.parent.mkdir(parents=True, exist_ok=True)
            source = seed.meshes[name]
            if isinstance(source, bytes):
                path.write_bytes(source)
            else:
                path.symlink_to(source)
    (folder / "scene.xml").write_bytes(xml)
    return Variant(index, seed.name, integrator, "+".join(mutations), folder)


def run_variant(render: Path, v: Variant, timeout: float) -> tuple[str, str]:
    return judge(render, v.folder / "scene.xml", v.integrator, timeout)


def save_finding(v: Variant, render: Path, outcome: str, detail: str, save: Path) -> Path:
    """Copy the variant (meshes resolved) into save/<outcome>-<index>/ with a note on how to reproduce it."""
    dest = save / f"{outcome}-{v.index}"
    shutil.rmtree(dest, ignore_errors=True)
    special = shutil.ignore_patterns("FIFO", "DIR", "mesh.ply", "out.exr")

    def ignore(folder: str, names: list[str]) -> set[str]:
        # mesh.obj is replay's own unless the variant mutated it (a seed's mesh).
        unchanged = folder == str(v.folder) and (v.folder / "mesh.obj").read_bytes() == OBJ_MESH
        return special(folder, names) | ({"mesh.obj"} if unchanged else set())

    shutil.copytree(v.folder, dest, symlinks=False, ignore=ignore)
    cmd = " ".join(render_command(Path("build/render"), dest / "scene.xml", v.integrator, dest / "out.exr"))
    (dest / "integrator").write_text(v.integrator + "\n")
    (dest / "README.txt").write_text(f"{outcome}: {detail}\nseed scene {v.seed}, mutation {v.mutation}, "
                                     f"integrator {v.integrator}\nreproduce (after tests/fuzz/replay.py has added "
                                     f"FIFO, DIR, mesh.obj and mesh.ply): {cmd}\n")
    return dest


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__.split("\n\n", 2)[2])
    p.add_argument("--runs", type=int, default=2000, help="variants to try (default 2000)")
    p.add_argument("--seed", type=int, default=1, help="campaign seed (default 1)")
    p.add_argument("--render", type=Path, default=ROOT / "build/render", help="the render binary (default build/render)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2, help="renders at once (default: cores)")
    p.add_argument("--timeout", type=float, default=120.0, help="seconds before a render counts as a hang (120)")
    p.add_argument("--work", type=Path, default=ROOT / ".fuzz", help="scratch folder (default .fuzz)")
    p.add_argument("--save", type=Path, default=ROOT / "tests/fuzz/crashes", help="where findings go")
    p.add_argument("--json", type=Path, help="write the outcome table and findings as JSON here")
    args = p.parse_args(argv)
    if not args.render.is_file():
        print(f"error: {args.render} does not exist: build it first (make build)", file=sys.stderr)
        return 2
    seeds = load_seeds()
    args.work.mkdir(parents=True, exist_ok=True)
    counts: Counter[str] = Counter()
    findings: list[dict] = []
    by_mutation: Counter[tuple[str, str]] = Counter()
    by_integrator: Counter[tuple[str, str]] = Counter()
    start = time.perf_counter()

    def one(index: int) -> None:
        v = make_variant(index, args.seed, seeds, args.work)
        outcome, detail = run_variant(args.render.resolve(), v, args.timeout)
        counts[outcome] += 1
        by_mutation[(v.mutation.split("+")[0], outcome)] += 1
        by_integrator[(v.integrator, outcome)] += 1
        if outcome in FINDINGS:
            dest = save_finding(v, args.render, outcome, detail, args.save)
            findings.append({"index": index, "outcome": outcome, "detail": detail, "seed_scene": v.seed,
                             "mutation": v.mutation, "integrator": v.integrator, "saved": str(dest)})
            print(f"\n{outcome}: variant {index} ({v.seed}, {v.mutation}, {v.integrator}): {detail} -> {dest}",
                  file=sys.stderr)
        shutil.rmtree(v.folder, ignore_errors=True)
        done = sum(counts.values())
        if sys.stderr.isatty() or done % 500 == 0 or done == args.runs:
            rate = done / max(time.perf_counter() - start, 1e-9)
            print(f"\r{done}/{args.runs} variants, {rate:.1f}/s, eta {(args.runs - done) / rate:.0f} s, "
                  f"{len(findings)} findings", end="" if sys.stderr.isatty() else "\n", file=sys.stderr, flush=True)

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        list(pool.map(one, range(args.runs)))
    seconds = time.perf_counter() - start
    print(file=sys.stderr)
    print("| outcome | count |\n|---|---|")
    for outcome in OUTCOMES:
        print(f"| {outcome} | {counts[outcome]} |")
    print("\n" + ", ".join(f"{i}: {by_integrator[(i, 'image')]} images, {by_integrator[(i, 'error')]} errors"
                            for i in INTEGRATORS))
    print(f"\n{args.runs} variants (seed {args.seed}) in {seconds:.0f} s with {args.render}; "
          f"{len(findings)} findings{' saved under ' + str(args.save) if findings else ''}")
    if args.json:
        args.json.write_text(json.dumps({"runs": args.runs, "seed": args.seed, "seconds": round(seconds, 1),
                                         "render": str(args.render), "outcomes": dict(counts),
                                         "by_mutation": {f"{m}:{o}": n for (m, o), n in sorted(by_mutation.items())},
                                         "by_integrator": {f"{i}:{o}": n for (i, o), n in sorted(by_integrator.items())},
                                         "findings": findings}, indent=2) + "\n")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
