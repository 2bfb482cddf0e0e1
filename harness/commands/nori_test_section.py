"""Nori's BSDF test files in `bsdfs --nori-test`: each `<bsdf>` mapped onto a BSDF of the library under test (ours
by default) and judged by Nori's own test (harness/bsdfs/nori_tests.py); mcval's matrix then runs on the same
BSDFs (harness/commands/bsdfs.py)."""
from __future__ import annotations

from pathlib import Path

from harness.commands.output import console
from harness.engines.nori.values import LUMINANCE
from harness.verdict import Tally

#: Nori's defaults of the BSDFs its tests use (src/microfacet.cpp, src/diffuse.cpp, src/dielectric.cpp).
NORI_DEFAULTS = {
    "microfacet": {"alpha": (0.1,), "intIOR": (1.5046,), "extIOR": (1.000277,), "kd": (0.5, 0.5, 0.5)},
    "diffuse": {"albedo": (0.5, 0.5, 0.5)},
    "dielectric": {"intIOR": (1.5046,), "extIOR": (1.000277,)},
}
#: Nori's property names as the ABI's BSDFs name them, where a library does not use Nori's own.
NORI_NAMES = {"intIOR": "int_ior", "extIOR": "ext_ior", "albedo": "reflectance"}


def _luminance(v: tuple[float, ...]) -> float:
    return v[0] if len(v) == 1 else sum(c * w for c, w in zip(v, LUMINANCE))


def library_values(bsdf, parameters: list[str]) -> dict[str, float]:
    """The library parameters of a Nori `<bsdf>` (harness/engines/nori/test_files.NoriBsdf): each property under
    its own name or NORI_NAMES', a colour as its luminance; a microfacet's kd also gives ks = 1 - max(kd), as Nori
    derives it, where the library takes ks. ValueError (one line, the element's place) for what cannot map."""
    given = {**NORI_DEFAULTS.get(bsdf.type, {}), **bsdf.properties}
    values: dict[str, float] = {}
    for name, value in given.items():
        target = name if name in parameters else NORI_NAMES.get(name, name)
        if target not in parameters:
            if name in bsdf.properties:
                raise ValueError(f"{bsdf.where}: <bsdf type=\"{bsdf.type}\">: the library's {bsdf.type} has no "
                                 f"parameter {name!r} (it takes {', '.join(parameters) or 'none'})")
            continue
        values[target] = _luminance(value)
    if bsdf.type == "microfacet" and "kd" in given and "kd" in parameters:
        kd = given["kd"]
        if "ks" in parameters:
            values.setdefault("ks", 1.0 - max(kd))
        elif max(kd) != min(kd):  # one gray kd gives both the diffuse albedo and ks = 1 - kd
            raise ValueError(f"{bsdf.where}: <bsdf type=\"microfacet\">: kd {kd} is coloured: its luminance and "
                             "Nori's ks = 1 - max(kd) differ, and the library's microfacet takes no ks parameter")
    return values


def run_nori_tests(paths: list[Path], library, seed: int) -> tuple[Tally, dict, list]:
    """Each file's BSDFs under Nori's test; returns the tally of Nori's verdicts, the results.json block and the
    BSDFs (as matrix specs) for mcval's own checks."""
    from rich.markup import escape

    from harness.bsdfs.nori_tests import run_chi2test, run_ttest
    from harness.bsdfs.suite import BsdfSpec
    from harness.engines.nori.test_files import read_nori_test

    tests = [read_nori_test(p) for p in paths]  # every file read before any runs: a typo fails at once
    scene_test = next((t for t in tests if t.scenes), None)
    if scene_test is not None:
        raise ValueError(f"{scene_test.path}: a ttest of scenes, not of BSDFs: run it with "
                         f"`images --nori-test {scene_test.path}`")
    mapped = [[BsdfSpec(b.type, tuple(library_values(b, library.parameters(b.type)).items())) for b in t.bsdfs]
              for t in tests]
    block, specs, passed, failed = [], [], 0, 0
    for test, bsdfs in zip(tests, mapped):
        functions = [library.functions(b.name, b.values(library.parameters(b.name))) for b in bsdfs]
        specs += bsdfs
        console.print(f"Nori's {test.kind}: {test.path} ({len(functions)} BSDFs)")
        if test.kind == "chi2test":
            verdicts = run_chi2test(functions, test.properties, seed)
        else:
            verdicts = run_ttest(functions, test.floats("angles"), test.floats("references"), test.properties, seed)
        for v in verdicts:
            mark = "[green]PASS[/]" if v.passed else "[red]FAIL[/]"
            console.print(f"  {mark} {escape(v.bsdf)}, {v.what}: {escape(v.message)}", soft_wrap=True)
        ok = sum(v.passed for v in verdicts)
        console.print(f"  Passed {ok}/{len(verdicts)} tests.")
        passed, failed = passed + ok, failed + len(verdicts) - ok
        block.append({"file": str(test.path), "kind": test.kind, "tests": [v.to_json() for v in verdicts]})
    return Tally("Nori's BSDF tests", passed, failed), {"nori_tests": block}, specs
