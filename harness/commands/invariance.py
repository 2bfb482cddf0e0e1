"""`invariance`: metamorphic checks, each engine against itself under physical transformations."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.commands.options import add_common, add_reference_live, add_engines, add_scene_files, add_variant
from harness.commands.output import print_verdict
from harness.commands.run_folder import RunFolder
from harness.distributed.cluster import add_executor_options
from harness.verdict import Verdict, run_verdict

NAME = "invariance"
HELP = "metamorphic checks: each engine against itself under physical transformations"
DESCRIPTION = """\
Render each scene and a rewritten copy of it with each engine (the tested one, then the reference) as independent
batches, and compare the copy's image, mapped back by what physics says, with the original's by the
image suite's Welch tests (pixel, tile, image). No reference image is involved. The rewrites
(harness/invariance/rewrite.py) apply to any scene file:
  scale        everything x 1e-3 and x 1e3 about the origin (point intensity x s^2, clip
               distances x s): same image
  rotate       everything by 37 deg about a unit axis: same image, normals rotated
  translate    everything by (10, -20, 30): same image (further away, float32 rounding of the
               scene itself is resolved by the tests; the report says where it starts)
  light        every emitter x 2: image x 2 (simple, ao)
  reflectance  every diffuse reflectance x 1/2: image x 1/2 (simple, ao)
Our renderer breaking an invariance fails the run (exit 1); Mitsuba breaking one is a finding,
printed and stored in results.json (invariance.findings). Mitsuba's cells do not depend on the
renderer under test: rendered at the references' seed, they are read from references/mitsuba/
where `make references` stored them for the same scenes, Mitsuba and check code (and rendered,
with the reason, where not; --reference-live renders them all). A break on a rewritten scene that
float32 cannot represent (a small sphere moved far from the origin, judged from the file, not from
the engine's answer) is FLOAT32: reported with the numbers, not a failure. A base render that is
all 0 leaves its cells not judged (no signal); base batches that are one image where the estimator
has noise fail them (is the seed used?); a run that judged no cell exits 3. Default cases: every
scene of scenes/ and scenes/real/ with each of simple, ao and normals that applies, at 64x64;
`validate` runs the same section."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.description = DESCRIPTION
    add_common(p)
    add_engines(p)
    p.add_argument("--only", nargs="+", metavar="NAME",
                   help="scenes, integrators, scene:integrator cases or invariances, e.g. crevice ao scale "
                        "(a kind not named means all of it)")
    p.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")
    p.add_argument("--no-mitsuba", action="store_true", help="check the engine under test alone")
    add_reference_live(p)
    add_scene_files(p)
    add_variant(p)
    add_executor_options(p)


def run(args: argparse.Namespace, run: RunFolder) -> Verdict:
    from harness.commands.invariance_section import run_invariance_section
    from harness.distributed.cluster import open_executor
    from harness.commands.options import case_selection
    from harness.invariance.suite import select

    with open_executor(args) as executor:
        select(args.only, **case_selection(args))  # bad names: no run
        run_dir = run.start()
        tally, invariance = run_invariance_section(args, args.only, run_dir, executor)
        verdict, reason = run_verdict([tally])
        run.finish({"run": run_dir.name, "pass": verdict is Verdict.PASS, "verdict": verdict.value,
                    "verdict_reason": reason, "invariance": invariance}, index=("invariance.html", "Invariances"),
                   json_copy=args.json)
    print_verdict(run_dir / "results.json", verdict, reason)
    return verdict
