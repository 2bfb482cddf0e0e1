"""The command line: `mcval COMMAND` (or `python -m harness COMMAND`), the commands of harness/commands/ under
one parser, and what every run shares: exit statuses, Ctrl-C and SIGTERM, and naming the partial output of an
unfinished run."""
from __future__ import annotations

import argparse
import signal
import sys
import threading
from pathlib import Path

from rich.markup import escape

from harness.commands import COMMANDS
from harness.commands.output import err
from harness.commands.run_folder import RunFolder
from harness.verdict import Verdict

#: The exit status of each verdict a command returns: the one place a run's outcome becomes a number.
EXIT_STATUS = {Verdict.PASS: 0, Verdict.FAIL: 1, Verdict.NOTHING_JUDGED: 3}

EPILOG = ("Each command but `references` writes results/<run>/ (results.json, HTML pages, junit.xml); "
          "results/latest moves to it once the run is complete. Exit status: 1 if any check fails, 3 if "
          "nothing was judged (no case ran, or every one was skipped or inconclusive: the run says why), 2 on "
          "bad input or an error, 130 if interrupted. Our renderer, Mitsuba's renders and a --warp-library "
          "run in child processes: a crash, kill or hang fails that case or warp only. Environment: "
          "MCVAL_RENDER, the `render` binary (default: build/render); MCVAL_RENDER_TIMEOUT, seconds per render "
          "(default: 600 plus a share per sample); MCVAL_MITSUBA_TIMEOUT, seconds per Mitsuba render (default: "
          "3600); MCVAL_WARP_TIMEOUT, seconds per call into a --warp-library (default: 120).")


def build_parser() -> argparse.ArgumentParser:
    """Every command and option of `mcval`, with its help."""
    p = argparse.ArgumentParser(
        prog="mcval",
        description="mcval: validate a Monte Carlo renderer against its pdfs and against Mitsuba 3.",
        epilog=EPILOG)
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        q = sub.add_parser(command.NAME, help=command.HELP)
        command.add_arguments(q)
        q.set_defaults(run=command.run)
    return p


def main(argv: list[str] | None = None) -> int:
    """Exit status: 0 all pass, 1 a check failed, 3 nothing was judged (EXIT_STATUS), 2 bad input or an error,
    130 interrupted (Ctrl-C). An unfinished run leaves its partial folder and does not move results/latest."""
    args = build_parser().parse_args(argv)
    run = RunFolder(getattr(args, "out", Path("results")))
    # SIGTERM (a CI time-out, `kill`) ends the run as Ctrl-C does: the render child is stopped and
    # the partial output is named.
    in_main_thread = threading.current_thread() is threading.main_thread()
    old_term = signal.signal(signal.SIGTERM, _raise_interrupt) if in_main_thread else None
    try:
        outcome = args.run(args, run)
        return EXIT_STATUS[outcome] if isinstance(outcome, Verdict) else outcome
    except (KeyboardInterrupt, Exception) as e:
        if _interrupted(e):
            err.print(escape(run.unfinished("interrupted")), soft_wrap=True)
            return 130
        if isinstance(e, (RuntimeError, ValueError)):
            err.print(f"[bold red]error:[/] {escape(str(e))}", soft_wrap=True)
        else:
            err.print_exception()
    finally:
        if in_main_thread:
            signal.signal(signal.SIGTERM, old_term)
    if run.path is not None:
        err.print(escape(run.unfinished("stopped")), soft_wrap=True)
    return 2


def _interrupted(e: BaseException | None) -> bool:
    """Whether `e` was raised because of a Ctrl-C or SIGTERM: a library may wrap the KeyboardInterrupt
    (Dr.Jit's import, interrupted, raises an ImportError from it)."""
    while e is not None:
        if isinstance(e, KeyboardInterrupt):
            return True
        e = e.__cause__ or e.__context__
    return False


def _raise_interrupt(signum: int, frame) -> None:
    raise KeyboardInterrupt(signal.Signals(signum).name)


if __name__ == "__main__":
    sys.exit(main())
