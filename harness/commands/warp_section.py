"""The warp conformance matrix as a section of a run (`warps`, `validate`): run, print, write its page."""
from __future__ import annotations

import platform
import time
from pathlib import Path

from rich.markup import escape

from harness.commands.output import console, progress_bar
from harness.statistics.constants import WARP_SAMPLES


def warp_engine(args):
    """The engine whose warps are checked: the --warp-library, else the engine under test. Made once per run
    and kept on `args` (loading a library, reading an engine file)."""
    if "_warp_engine" not in vars(args):
        library = getattr(args, "warp_library", None)
        if library is not None:
            from harness.engines.warp_library import WarpLibraryEngine
            args._warp_engine = WarpLibraryEngine(library)
        else:
            from harness.engines.registry import make_engine
            args._warp_engine = make_engine(args.engine)
    return args._warp_engine


def available_specs(engine, specs) -> tuple[list, list[str]]:
    """The specs `engine` can be checked on, and one line for each it cannot (a sampler without its pdf).
    A warp an optional engine (a user's library) lacks is left out; one the tested engine lacks stays, and fails."""
    from harness.engines.python_child import ChildFailed
    from harness.engines.warp_library import WarpUnavailable

    kept, problems = [], []
    for spec in specs:
        try:
            functions = engine.warp(spec.name, spec.alpha)
        except ChildFailed:  # a library that could not be loaded: each warp asked for fails in its own row
            kept.append(spec)
            continue
        except WarpUnavailable as e:
            if str(e) not in problems:
                problems.append(str(e))
            continue
        if functions is not None or not engine.warps_optional:
            kept.append(spec)
    return kept, problems


class WarpSection:
    """The warp matrix of a run: every warp of `specs` against its pdf and, unless --no-mitsuba, against
    Mitsuba's. Its checks run on a thread of their own from construction on, so that the section run next (the
    BSDF rows, which leave a core partly idle) runs beside them; `finish` waits for them, then times each warp's
    throughput alone (timed beside other work, a rate would measure the machine's load), prints the table and
    writes the page."""

    def __init__(self, args, specs) -> None:
        from concurrent.futures import ThreadPoolExecutor

        from harness.engines.registry import make_engine
        from harness.warps.suite import run_matrix

        self.args, self.asked_for = args, specs
        self.tested = warp_engine(args)
        self.specs, self.problems = available_specs(self.tested, specs)
        for line in self.problems:
            console.print(f"[red]FAIL[/] {escape(line)}", soft_wrap=True)
        self.reference = None if getattr(args, "no_mitsuba", False) else make_engine(args.reference)
        self.samples = getattr(args, "samples", WARP_SAMPLES)
        self.done, self.last = 0, ""
        self._start = time.perf_counter()
        self._pool = ThreadPoolExecutor(1, thread_name_prefix="warps")
        self._matrix = self._pool.submit(run_matrix, self.tested, self.reference, self.specs, seed=args.seed,
                                         samples=self.samples, on_progress=self._checked, timed=False)

    def _checked(self, spec) -> None:
        self.done, self.last = self.done + 1, spec.key

    def _wait(self):
        """The matrix's (results, level), with a bar of the warps checked while it is not done."""
        try:
            with progress_bar("warps") as progress:
                task, shown = progress.add_task("", total=len(self.specs)), 0
                while True:
                    try:
                        return self._matrix.result(timeout=0.2)
                    except TimeoutError:
                        if self.done != shown:
                            shown = self.done
                            progress.update(task, completed=shown, description=self.last)
        finally:
            self._pool.shutdown()

    def finish(self, run_dir: Path) -> tuple[bool, dict]:
        """Wait for the checks, time the throughput, print and write the section; returns (all pass, the
        results.json block)."""
        from harness.report.reproduce import invocation
        from harness.report.warp_outputs import warp_payload, write_warp_outputs
        from harness.report.warp_table import warp_table
        from harness.warps.suite import time_matrix

        args, tested, reference, specs = self.args, self.tested, self.reference, self.specs
        results, level = self._wait()
        with progress_bar("warps: throughput") as progress:
            task = progress.add_task("", total=len(specs))
            results = time_matrix(tested, reference, specs, results, args.seed,
                                  on_progress=lambda s: progress.update(task, advance=1, description=s.key))
        seconds = time.perf_counter() - self._start
        meta = {"engine": tested.version(), "reference": reference.version() if reference else "none",
                "samples per warp": self.samples, "seed": args.seed, "seconds": round(seconds, 2),
                "machine": f"{platform.machine()}, {platform.system()} {platform.release()}"}
        nothing = None
        if results:
            console.print(warp_table(results, level))
        else:
            asked = ", ".join(dict.fromkeys(spec.name for spec in self.asked_for))
            nothing = f"{tested.name} exports none of the warps asked for ({asked})"
            console.print(f"[red]No warp judged[/]: {escape(nothing)}")
        paths = write_warp_outputs(run_dir, specs, results, level, meta, args.seed, invocation(args))
        failed = [r for r in results if not r.passed]
        console.print(f"{len(results) - len(failed)} of {len(results)} warps pass, in {seconds:.1f} s. "
                      f"Page: {paths['html']}")
        for r in results:
            if r.failure:
                console.print(f"[red]FAIL[/] {escape(r.failure)}", soft_wrap=True)
            elif not r.passed:
                console.print(f"[red]FAIL[/] {r.label}: data in {run_dir / 'warps'}")
        payload = warp_payload(results, level, meta)
        payload["problems"] = self.problems
        if nothing:
            payload["nothing_judged"] = nothing
        payload["pass"] = ok = payload["pass"] and not self.problems and bool(results)
        return ok, payload
