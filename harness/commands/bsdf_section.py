"""The BSDF matrix as a section of a run (`bsdfs`, `validate`): the BSDFs asked for, run, printed, and its
results.json block, JUnit file and tally."""
from __future__ import annotations

from pathlib import Path

from harness.commands.output import console, task_progress
from harness.verdict import Tally

#: Our renderer's BSDFs, built as a library of include/mcval_bsdfs.h.
OUR_LIBRARY = Path(__file__).resolve().parents[2] / "build" / "libmcval_bsdfs.so"


def bsdf_library_of(args):
    """The library whose BSDFs are checked: --bsdf-library, else ours where the engine under test is ours; None
    for another engine without a library (it has no BSDFs to check)."""
    from harness.engines.bsdf_library import BsdfLibrary
    from harness.engines.registry import DEFAULT_TEST

    if getattr(args, "bsdf_library", None) is not None:
        return BsdfLibrary(args.bsdf_library)
    engine = getattr(args, "engine", None) or DEFAULT_TEST
    return BsdfLibrary(OUR_LIBRARY) if engine == DEFAULT_TEST else None


def null_row_functions(library: str, against_mitsuba: bool, spec_text: str):
    """A calibration row's BSDF from `library` (a path) and Mitsuba's plugin of its name where asked and there is
    one (harness/bsdfs/calibration.py: bound with functools.partial, it travels to a cluster's workers)."""
    from harness.bsdfs.suite import parse_spec
    from harness.engines.bsdf_library import BsdfLibrary
    from harness.engines.mitsuba_bsdfs import MitsubaBsdfs

    spec, lib = parse_spec(spec_text), BsdfLibrary(Path(library))
    values = spec.values(lib.parameters(spec.name))
    return lib.functions(spec.name, values), MitsubaBsdfs().functions(spec.name, values) if against_mitsuba else None


def _usable_reference(mitsuba, name: str, values: dict):
    """Mitsuba's plugin `name` at `values`, or None where it has none or refuses the values (a reflectance of 2):
    then the BSDF is checked on its own, and a line says why."""
    import numpy as np
    from rich.markup import escape

    from harness.engines.python_child import ChildFailed, ChildRaised
    from harness.foreign_text import one_line

    reference = mitsuba.functions(name, values)
    if reference is None:
        return None
    try:
        reference.eval(np.array([[0.0, 0.0, 1.0]]), np.array([[0.0, 0.0, 1.0]]))
    except (ChildRaised, ChildFailed) as e:
        given = " ".join(f"{k}={v:g}" for k, v in values.items())
        console.print(f"[yellow]Mitsuba's {name} refuses {escape(given)}[/] "
                      f"({escape(one_line(e.reason, 320))}): checked without it", soft_wrap=True)
        return None
    return reference


def _say_guessed(spec, values: dict) -> None:
    """One line for the parameters neither given nor named in DEFAULT_VALUES, which get FALLBACK_VALUE: a value
    picked for a name the harness does not know may mean nothing for that BSDF."""
    from harness.bsdfs.suite import DEFAULT_VALUES, FALLBACK_VALUE

    guessed = [p for p in values if p not in dict(spec.given) and p not in DEFAULT_VALUES]
    if guessed:
        example = ",".join(f"{p}=..." for p in guessed)
        console.print(f"{spec.name}: {', '.join(guessed)} not given, checked at {FALLBACK_VALUE:g} (give "
                      f"--bsdf {spec.name}:{example})", soft_wrap=True)


def _entries(specs, library, mitsuba) -> list:
    """The BSDFs asked for (`specs`, parsed; None for the default set), each ready or with the one line saying why
    it cannot be checked."""
    from harness.bsdfs.hard_inputs import roughness_extremes
    from harness.bsdfs.suite import OUR_DEFAULTS, Entry, parse_spec
    from harness.engines.bsdf_library import BsdfUnavailable

    if specs is None:  # ours and Mitsuba's (the plugins of our names) at their set of values, a user's at defaults
        ours = [parse_spec(t) for t in OUR_DEFAULTS]
        specs = ([s for s in ours if s.name in library.names] if library.path in (OUR_LIBRARY, None)
                 else [parse_spec(t) for t in library.names])
    entries = []
    for spec in specs:
        try:
            values = spec.values(library.parameters(spec.name))
            bsdf = library.functions(spec.name, values)
        except (BsdfUnavailable, ValueError) as e:
            entries.append(Entry(spec.name, failure=str(e)))
            continue
        _say_guessed(spec, values)
        reference = None if mitsuba is None else _usable_reference(mitsuba, spec.name, values)
        extremes = roughness_extremes(lambda v, name=spec.name: library.functions(name, v), values)
        entries.append(Entry(bsdf.label, bsdf, reference, extremes=extremes))
    return entries


def run_bsdf_section(library, specs, angles, samples: int, seed: int, alpha: float, mitsuba: bool, run_dir: Path,
                     junit_name: str = "junit.xml", jobs: int | None = None) -> tuple[Tally, dict]:
    """The matrix of `library`'s BSDFs `specs` (None: the default set), against Mitsuba's plugins if `mitsuba`
    (not when the library is Mitsuba's: harness/engines/mitsuba_bsdfs.py), `jobs` rows at once (default: one per
    core); prints its table and one line per failed row, writes its JUnit file; returns its tally and results.json
    block."""
    import os

    from rich.markup import escape

    from harness.bsdfs.suite import run_matrix
    from harness.distributed.executor import ThreadExecutor
    from harness.engines.mitsuba_bsdfs import MitsubaBsdfs
    from harness.report.bsdf_html import bsdf_report_html
    from harness.report.bsdf_outputs import bsdf_junit, bsdf_table

    against_mitsuba = mitsuba and library.path is not None
    entries = _entries(specs, library, MitsubaBsdfs() if against_mitsuba else None)
    # Threads: a row waits mostly on the library's and Mitsuba's processes (a child each per thread) and in numpy.
    executor = ThreadExecutor(jobs or os.cpu_count() or 1)
    with task_progress("bsdf rows", executor) as on_status:
        rows, level = run_matrix(entries, angles, samples, seed, alpha, executor, on_status)
    console.print(bsdf_table(rows, level))
    for row in rows:
        if not row.passed:
            where = "" if row.theta is None else f" at {row.theta:g} degrees"
            lines = [row.failure] if row.failure else [f"{k}: {c.summary}" for k, c in row.checks.items() if not c.passed]
            console.print(f"[red]FAIL[/] {escape(row.label + where + ': ' + '; '.join(lines))}", soft_wrap=True)
    passed = sum(r.passed for r in rows)
    meta = {"library": library.version(), "reference": "Mitsuba 3 plugins" if against_mitsuba else "none",
            "samples": samples, "seed": seed, "alpha": alpha, "level": level}
    (run_dir / junit_name).write_text(bsdf_junit(rows, meta))
    (run_dir / "bsdfs.html").write_text(bsdf_report_html(rows, level, meta))
    console.print(f"{passed} of {len(rows)} BSDF rows pass; histograms and residuals: {run_dir / 'bsdfs.html'}")
    return Tally("BSDF rows", passed, len(rows) - passed), {"bsdfs": [r.to_json() for r in rows], "bsdf_level": level,
                                                             "bsdf_meta": meta}
