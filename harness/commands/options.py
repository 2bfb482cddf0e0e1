"""Options that several commands share."""
from __future__ import annotations

import argparse
from pathlib import Path

from harness.distributed.cluster import add_executor_options


def add_common(q: argparse.ArgumentParser) -> None:
    """--out and --seed: every command that writes a run folder."""
    q.add_argument("--out", type=Path, default=Path("results"), help="folder for run folders (default: results)")
    q.add_argument("--seed", type=int, default=0, help="seed of every random choice (default: 0)")


def add_case_choice(q: argparse.ArgumentParser, default: str) -> None:
    """--scenes/--only: the image cases to run; --scene: scene files of one's own."""
    q.add_argument("--scenes", "--only", dest="scenes", nargs="+", metavar="CASE",
                   help=f"scenes, integrators or scene:integrator cases, e.g. cornell ao plane_point:simple "
                        f"cornell_box (default: {default})")
    add_scene_files(q)
    q.add_argument("--resolution", type=int, metavar="N",
                   help="with --scene: render your scenes N pixels wide, the height keeping the film's aspect "
                        "(default: 128, the suite's)")


def add_scene_files(q: argparse.ArgumentParser) -> None:
    q.add_argument("--scene", action="append", type=Path, metavar="PATH",
                   help="a scene file of your own, or a folder of them (repeatable); rendered instead of the "
                        "built-in scenes, from a prepared copy under --out: nothing is written beside it")
    q.add_argument("--with-suite", action="store_true", help="with --scene: the built-in scenes too")


def case_selection(args: argparse.Namespace) -> dict:
    """What selects the cases, as keyword arguments of select_cases: the tested engine's integrators and the
    scenes of --scene (prepared under --out/.scenes). Worked out once per run and kept on `args`: the
    sections of one run each ask for it."""
    if "_case_selection" not in vars(args):
        args._case_selection = _case_selection(args)
    return args._case_selection


def _case_selection(args: argparse.Namespace) -> dict:
    user = None
    if getattr(args, "scene", None):
        from rich.markup import escape

        from harness.commands.output import err
        from harness.commands.reference_image_options import check_reference_image, reference_image
        from harness.images.references import RESOLUTION
        from harness.images.user_scenes import prepare_scenes
        check_reference_image(args)
        image = reference_image(args)
        width = getattr(args, "resolution", None) or RESOLUTION
        if width < 1:
            raise ValueError(f"--resolution {width}: expected a width of at least 1 pixel")
        # Against a reference image the scene renders at the image's size.
        user = prepare_scenes(args.scene, args.out / ".scenes", image.size[0] if image else width, skip=(args.out,))
        for note in (n for u in user for n in u.notes):
            err.print(f"[yellow]note:[/] {escape(note)}", soft_wrap=True)
    return {"integrators": tested_integrators(args), "user": user,
            "with_suite": getattr(args, "with_suite", False)}


def add_reference_live(q: argparse.ArgumentParser) -> None:
    q.add_argument("--reference-live", action="store_true",
                   help="render the reference engine's invariance cells now, at the references' seed, instead of "
                        "reading those stored in references/ for the same scenes, code and Mitsuba (`make "
                        "references` stores them)")


def add_variant(q: argparse.ArgumentParser) -> None:
    q.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (default: llvm_ad_rgb)")


def add_image_options(q: argparse.ArgumentParser) -> None:
    """What `images` and `validate` take: cases, the regression baseline, Mitsuba's variant, the executor."""
    add_case_choice(q, "all, scenes/ and scenes/real/")
    add_engines(q)
    q.add_argument("--baseline", type=Path, metavar="RESULTS_JSON",
                   help="compare with this run's results.json (default: the previous run's)")
    q.add_argument("--detect-bias", type=_bias, metavar="BIAS",
                   help="choose each case's samples per pixel so that a relative bias of the image mean of BIAS "
                        "(e.g. 0.5%%) is found 90 %% of the time, from a pilot render and the comparison's power "
                        "model; prints each case's budget and its cost before rendering (default: the "
                        "integrators' fixed budgets)")
    add_variant(q)
    add_executor_options(q)


def _bias(text: str) -> float:
    from harness.images.budget import parse_bias
    try:
        return parse_bias(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def add_warp_library(q: argparse.ArgumentParser) -> None:
    q.add_argument("--warp-library", type=Path, metavar="LIB.so",
                   help="check the warps this shared library exports (the C ABI of include/mcval_warps.h, see "
                        "docs/engines.md) instead of the engine's")


def tested_integrators(args: argparse.Namespace) -> tuple[str, ...] | None:
    """The integrators the engine under test renders (an engine file's table), None for every one."""
    from harness.engines.registry import DEFAULT_TEST, engine_integrators
    tested = getattr(args, "engine", None) or (getattr(args, "engines", None) or [DEFAULT_TEST])[0]
    return engine_integrators(tested)


def add_engines(q: argparse.ArgumentParser, test: bool = True, reference: bool = True) -> None:
    """--engine (the engine under test) and --reference (the engine it is compared with), by registry name
    (harness/engines/registry.py; more with $MCVAL_ENGINE_PATH)."""
    from harness.engines.registry import DEFAULT_REFERENCE, DEFAULT_TEST, PATH_ENV, engine_entries

    try:
        known = f"; known: {', '.join(engine_entries())}"
    except Exception as e:  # a broken engine file is reported when an engine is made, not by --help
        known = f"; ${PATH_ENV} has an error: {e}"
    known = known.replace("%", "%%")  # argparse formats help with %
    if test:
        q.add_argument("--engine", default=DEFAULT_TEST, metavar="NAME|FILE.toml",
                       help=f"the engine under test: a registered name or an engine file describing any renderer "
                            f"(docs/engines.md) (default: {DEFAULT_TEST}, this repository's renderer{known})")
    if reference:
        q.add_argument("--reference", default=DEFAULT_REFERENCE, metavar="NAME|FILE.toml",
                       help=f"the engine it is compared with, a name or an engine file (default: "
                            f"{DEFAULT_REFERENCE}, Mitsuba 3)")
