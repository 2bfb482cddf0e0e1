"""The command line's grammar: commands, options and their help (harness.cli runs them)."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.distributed.cluster import add_executor_options
from harness.statistics.constants import WARP_SAMPLES


def build_parser() -> argparse.ArgumentParser:
    """Every command and option of `python -m harness`, with its help."""
    p = argparse.ArgumentParser(
        prog="python -m harness",
        description="mcval: validate a Monte Carlo renderer against its pdfs and against Mitsuba 3.",
        epilog="Each command but `references` writes results/<run>/ (results.json, HTML pages, junit.xml); "
               "results/latest moves to it once the run is complete. Exit status: 1 if any check fails, 2 on "
               "bad input or an error, 130 if interrupted. Our renderer runs as a child process, one per "
               "render: a crash, kill or hang fails that case only. Environment: MCVAL_RENDER, the `render` "
               "binary (default: build/render); MCVAL_RENDER_TIMEOUT, seconds per render (default: 600 plus "
               "a share per sample).")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def common(q: argparse.ArgumentParser) -> None:
        q.add_argument("--out", type=Path, default=Path("results"), help="folder for run folders (default: results)")
        q.add_argument("--seed", type=int, default=0, help="seed of every random choice (default: 0)")

    def image_options(q: argparse.ArgumentParser) -> None:
        q.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE",
                       help="scenes, integrators or scene:integrator cases, e.g. cornell ao plane_point:simple "
                            "cornell_box (default: all, scenes/ and scenes/real/)")
        q.add_argument("--baseline", type=Path, metavar="RESULTS_JSON",
                       help="compare with this run's results.json (default: the previous run's)")
        q.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (default: llvm_ad_rgb)")
        add_executor_options(q)

    w = sub.add_parser("warps", help="the warp conformance matrix alone",
                       description="Check every warp of the renderer against its pdf (chi-square, normalisation, "
                                   "domain, hard inputs) and against Mitsuba 3's implementation.")
    common(w)
    w.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")
    w.add_argument("--only", nargs="+", metavar="WARP",
                   help="check only these warps, e.g. tent beckmann:0.01 (default: all)")
    w.add_argument("--samples", type=int, default=WARP_SAMPLES,
                   help=f"samples per warp for the statistical tests (default: {WARP_SAMPLES})")
    w.add_argument("--no-mitsuba", action="store_true", help="skip the checks against Mitsuba 3")

    i = sub.add_parser("images", help="every scene with every integrator against Mitsuba 3",
                       description="Render the scene suite with our renderer and compare with Mitsuba 3 "
                                   "(stored references when their provenance matches) and closed forms.")
    common(i)
    image_options(i)

    r = sub.add_parser("references", help="render and store Mitsuba references under references/",
                       description="Render Mitsuba 3 references (K batches) for the scene suite and store them "
                                   "with their provenance. The only command that writes references/.")
    r.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE", help="as for `images`")
    r.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (default: llvm_ad_rgb)")
    add_executor_options(r)

    b = sub.add_parser("bench", help="speed against error: convergence curves and efficiency ratios",
                       description="Render every case at a ladder of sample counts with our renderer and Mitsuba "
                                   "(llvm and scalar), several runs per step, one job at a time; write bench.html.")
    common(b)
    b.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE",
                   help="as for `images` (default: the simple and ao cases of every scene)")
    b.add_argument("--engines", nargs="+", default=["mcval", "mitsuba", "mitsuba-scalar"],
                   choices=["mcval", "mitsuba", "mitsuba-scalar"], help="engines to run (default: all three)")
    b.add_argument("--max-spp", type=int, default=256, help="top of the ladder 1, 2, 4, ... (default 256)")
    b.add_argument("--same-sampler", action="store_true",
                   help="only the engine comparison: every engine with the independent sampler (by default each "
                        "also runs its stratified samplers: ours sobol, Mitsuba ldsampler and multijitter)")
    b.add_argument("--runs", type=int, default=3, help="independent runs per step (default 3)")
    b.add_argument("--rays-json", type=Path, help="figures written by build/bench_rays --json, to include")
    b.add_argument("--throughput-runs", type=int, default=3,
                   help="timed runs per case of the side-by-side render throughput (highpoly 768², cornell 128²; "
                        "0 skips it; default 3)")
    b.add_argument("--seed-runs", type=int, default=3,
                   help="runs at the seed document's settings (768x768; 0 skips them; default 3)")
    add_executor_options(b)

    c = sub.add_parser("calibrate", help="measure the false-alarm rate of every statistical check",
                       description="Measure, not assume, how often each statistical check rejects when nothing is "
                                   "wrong. Warps: every correct warp of the matrix at many seeds (chi-square, "
                                   "homogeneity with Mitsuba). Images: null comparisons (ours against ours at "
                                   "independent seeds, Mitsuba against Mitsuba, ours against the closed form) per "
                                   "scale and for the whole comparison, and the smallest whole-image and 8x8-tile "
                                   "biases found 90 %% of the time. Each rate with an exact interval beside the "
                                   "nominal level. Writes calibration.html and calibration.json (blocks with "
                                   "`comparisons` and `false_alarm_rate`); results/calibration-latest points at the "
                                   "newest. Exits 1 if a rate lies above its nominal level beyond its interval (the check "
                                   "raises more false alarms than it says) or a comparison failed; a rate below its "
                                   "interval (conservative: it costs power, not false FAILs) is shown in yellow.")
    common(c)
    c.add_argument("--warps", action="store_true", help="calibrate the warp checks (with --images: both; the default)")
    c.add_argument("--images", action="store_true", help="calibrate the image comparisons (default: both)")
    c.add_argument("--only", nargs="+", metavar="WARP", help="only these warps, e.g. tent beckmann:0.01")
    c.add_argument("--seeds", type=int, default=200, help="null runs per warp (default 200)")
    c.add_argument("--samples", type=int, default=WARP_SAMPLES,
                   help=f"samples per run, as in the matrix (default {WARP_SAMPLES})")
    c.add_argument("--comparisons", type=int, default=80,
                   help="null image comparisons of each of the three kinds (default 80: 240 in all)")
    c.add_argument("--json", type=Path, metavar="PATH", help="also write the figures as JSON to PATH")
    c.add_argument("--no-mitsuba", action="store_true", help="skip the checks against Mitsuba (warps only)")
    add_executor_options(c)

    sub.add_parser("integrators", help="the renderer's integrators and what the harness knows of each",
                   description="List every integrator of the renderer's registry (mcval_renderer.integrators()) "
                               "with its harness entry (harness/integrators/<name>.py, or a .py file in a folder "
                               "of $MCVAL_INTEGRATOR_PATH): samples per pixel of our renders and of Mitsuba's "
                               "references, the Mitsuba integrator it is compared with and what is removed from "
                               "a scene for it, its closed form on one plane, and what it needs of a scene. An "
                               "integrator without an entry is listed as such (it is not validated); an entry "
                               "for an integrator the renderer lacks is an error (exit status 2).")

    n = sub.add_parser(
        "invariance", help="metamorphic checks: each engine against itself under physical transformations",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description=(
            "Render each scene and a rewritten copy of it with each engine (ours, then Mitsuba 3) as independent\n"
            "batches, and compare the copy's image, mapped back by what physics says, with the original's by the\n"
            "image suite's Welch tests (pixel, tile, image). No reference image is involved. The rewrites\n"
            "(harness/invariance/rewrite.py) apply to any scene file:\n"
            "  scale        everything x 1e-3 and x 1e3 about the origin (point intensity x s^2, clip\n"
            "               distances x s): same image\n"
            "  rotate       everything by 37 deg about a unit axis: same image, normals rotated\n"
            "  translate    everything by (10, -20, 30): same image (further away, float32 rounding of the\n"
            "               scene itself is resolved by the tests; the report says where it starts)\n"
            "  light        every emitter x 2: image x 2 (simple, ao)\n"
            "  reflectance  every diffuse reflectance x 1/2: image x 1/2 (simple, ao)\n"
            "Our renderer breaking an invariance fails the run (exit 1); Mitsuba breaking one is a finding,\n"
            "printed and stored in results.json (invariance.findings). A break on a rewritten scene that\n"
            "float32 cannot represent (a small sphere moved far from the origin, judged from the file, not from\n"
            "the engine's answer) is FLOAT32: reported with the numbers, not a failure. Default cases: every\n"
            "scene of scenes/ and scenes/real/ with each of simple, ao and normals that applies, at 64x64;\n"
            "`validate` runs the same section."))
    common(n)
    n.add_argument("--only", nargs="+", metavar="NAME",
                   help="scenes, integrators, scene:integrator cases or invariances, e.g. crevice ao scale "
                        "(a kind not named means all of it)")
    n.add_argument("--json", type=Path, metavar="PATH", help="also write the results as JSON to PATH")
    n.add_argument("--no-mitsuba", action="store_true", help="check our renderer alone")
    n.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (default: llvm_ad_rgb)")
    add_executor_options(n)

    v = sub.add_parser("validate", help="everything: what `make validate` runs",
                       description="Warp conformance, image validation (our scenes, then the real scenes of "
                                   "scenes/real/ as their own section) and the invariances (see `invariance "
                                   "--help`); writes results/<run>/report.html.")
    common(v)
    image_options(v)
    v.add_argument("--invariance-only", nargs="+", metavar="NAME",
                   help="narrow the Invariances section as `invariance --only` does (default: its default cases)")
    v.add_argument("--no-invariance", action="store_true", help="skip the Invariances section")
    return p
