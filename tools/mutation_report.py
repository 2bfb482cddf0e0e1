"""Summarise a mutmut run (mutants/**/*.meta) into results/mutation/: the kill rate per module and the
surviving mutants, as survivors.json and survivors.txt (with each survivor's diff).

    python tools/mutation_report.py [--out results/mutation] [--no-diffs] [module patterns, e.g. 'harness.statistics.welch*']

Mutants listed in tools/mutation_equivalent.txt (name, then a reason) are equivalent to the original
code: reported apart and not counted against the kill rate.
"""
from __future__ import annotations

import argparse
import fnmatch
import json
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KILLED = {1, 3, 36, -24, 24, 152, 255, 37}   # killed, pytest error, timeouts, type check
SURVIVED = {0}
NO_TESTS = {5, 33}


def equivalents() -> dict[str, str]:
    path = ROOT / "tests" / "mutation_equivalent.txt"
    out = {}
    if path.exists():
        for line in path.read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                name, _, reason = line.partition(" ")
                out[name] = reason.strip()
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(ROOT / "results" / "mutation"))
    ap.add_argument("--no-diffs", action="store_true")
    ap.add_argument("patterns", nargs="*", default=["*"])
    args = ap.parse_args(argv)
    equivalent = equivalents()
    modules: dict[str, Counter] = {}
    survivors, no_tests, documented = [], [], []
    for meta in sorted((ROOT / "mutants").rglob("*.py.meta")):
        try:
            codes = json.loads(meta.read_text()).get("exit_code_by_key", {})
        except ValueError:  # being written by a run in progress
            print(f"skipped {meta} (unreadable)", file=sys.stderr)
            continue
        for name, code in codes.items():
            if not any(fnmatch.fnmatch(name, p) for p in args.patterns):
                continue
            module = name.split(".x", 1)[0].split(".x\u01c1", 1)[0]
            c = modules.setdefault(module, Counter())
            if code is None:
                c["not checked"] += 1
            elif name in equivalent:
                c["equivalent"] += 1
                documented.append({"name": name, "reason": equivalent[name]})
            elif code in KILLED:
                c["killed"] += 1
            elif code in SURVIVED:
                c["survived"] += 1
                survivors.append(name)
            elif code in NO_TESTS:
                c["no tests"] += 1
                no_tests.append(name)
            else:
                c["suspicious"] += 1
                survivors.append(name)
    rates = {}
    for module, c in sorted(modules.items()):
        judged = c["killed"] + c["survived"] + c["no tests"] + c["suspicious"]
        rates[module] = {**c, "kill_rate": c["killed"] / judged if judged else None}
    diffs = {}
    if not args.no_diffs:
        for name in survivors + no_tests:
            res = subprocess.run([str(Path(sys.executable).parent / "mutmut"), "show", name], cwd=ROOT,
                                 capture_output=True, text=True)
            diffs[name] = res.stdout
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "survivors.json").write_text(json.dumps(
        {"modules": rates, "survived": survivors, "no_tests": no_tests, "equivalent": documented,
         "diffs": diffs}, indent=1))
    lines = ["module  killed/judged  kill rate  (not checked, equivalent)"]
    for module, r in rates.items():
        judged = r.get("killed", 0) + r.get("survived", 0) + r.get("no tests", 0) + r.get("suspicious", 0)
        rate = "-" if r["kill_rate"] is None else f"{r['kill_rate']:.1%}"
        lines.append(f"{module}  {r.get('killed', 0)}/{judged}  {rate}  ({r.get('not checked', 0)}, "
                     f"{r.get('equivalent', 0)})")
    lines += ["", f"survived ({len(survivors)}):"] + [f"  {n}" for n in survivors]
    lines += ["", f"no tests ({len(no_tests)}):"] + [f"  {n}" for n in no_tests]
    text = "\n".join(lines) + "\n"
    if diffs:
        text += "\n" + "\n".join(diffs.values())
    (out / "survivors.txt").write_text(text)
    print("\n".join(lines[: len(rates) + 1]))
    print(f"survivors: {len(survivors)}, no tests: {len(no_tests)} -> {out}/survivors.txt")
    return 0


if __name__ == "__main__":
    sys.exit(main())
