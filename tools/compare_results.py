"""Two results.json files compared field by field, except times and paths: every verdict, every string and
every number to 6 significant digits (--digits). Lists of cases (images, warps, invariance cells) are matched
by what they are (scene, integrator, engine, invariance, warp), not by position.

    .venv/bin/python -m tools.compare_results OLD.json NEW.json [--digits 6]

A field that only NEW has (one it adds) is not a difference; one that only OLD has is. Prints each difference
as a path and both values; exits 1 if there is any."""
from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

#: Keys whose values are times or paths (or hold them): not compared. A key starting with "/" is one field
#: (the engine's description in image_meta names the build folder).
SKIPPED = {"seconds", "image seconds", "run", "baseline", "data", "date", "meta", "ran on", "first_seconds",
           "median_seconds", "time_to_target", "regression", "throughput", "phase_seconds", "wall_seconds",
           "phases before the images", "invocation", "/image_meta/engine"}
#: What tells the items of a list of cases apart (a list whose items all have some of these is matched by them).
IDENTITY = ("engine", "invariance", "scene", "integrator", "warp", "params", "label", "name", "kind", "case")


#: Significant digits two numbers must share (--digits).
DIGITS = 6


def _same_number(a: float, b: float, digits: int = DIGITS) -> bool:
    """Equal to `digits` significant digits: the same when printed so, or apart by at most 0.5 * 10^-digits of
    the larger (1.0000004 and 0.9999997 print differently and are still one number to 6 digits)."""
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(a) or math.isinf(b):
        return a == b
    return f"{a:.{digits}g}" == f"{b:.{digits}g}" or abs(a - b) <= 0.5 * 10.0 ** -digits * max(abs(a), abs(b))


def _key(item, fields: list[str]) -> tuple | None:
    if isinstance(item, dict) and fields:
        return tuple((k, json.dumps(item[k], sort_keys=True)) for k in fields)
    return None


def _number(v):
    """A JSON number, or a NaN/Inf written as a string, as a float; anything else as it is."""
    if isinstance(v, bool):
        return v
    if isinstance(v, (int, float)):
        return float(v)
    if v in ("nan", "inf", "-inf", "NaN", "Infinity", "-Infinity"):
        return float(v.replace("Infinity", "inf"))
    return v


def compare(old, new, path: str = "", digits: int = DIGITS) -> list[str]:
    """Each difference between `old` and `new` as one line; numbers compared to `digits` significant digits."""
    if isinstance(old, dict) and isinstance(new, dict):
        out = []
        for k in sorted(set(old) | set(new)):
            if k in SKIPPED or f"{path}/{k}" in SKIPPED:
                continue
            if k not in new:
                out.append(f"{path}/{k}: only in the first")
            elif k not in old:
                continue  # a field the first did not have
            else:
                out += compare(old[k], new[k], f"{path}/{k}", digits)
        return out
    if isinstance(old, list) and isinstance(new, list):
        # Identity fields that every item of both lists has (a field NEW adds does not tell items apart).
        fields = [k for k in IDENTITY if all(isinstance(x, dict) and k in x for x in old + new)]
        keys_old, keys_new = [_key(x, fields) for x in old], [_key(x, fields) for x in new]
        if all(keys_old) and all(keys_new) and len(set(keys_old)) == len(old) and len(set(keys_new)) == len(new):
            by_new = dict(zip(keys_new, new))
            out = [f"{path}[{dict(k)}]: only in the first" for k in keys_old if k not in by_new]
            out += [f"{path}[{dict(k)}]: only in the second" for k in keys_new if k not in dict(zip(keys_old, old))]
            for k, item in zip(keys_old, old):
                if k in by_new:
                    where = "/".join(json.loads(v) if isinstance(json.loads(v), str) else v for _, v in k)
                    out += compare(item, by_new[k], f"{path}[{where}]", digits)
            return out
        if len(old) != len(new):
            if all(isinstance(x, str) for x in old + new) and sorted(old) == sorted(new):
                return []
            return [f"{path}: {len(old)} items against {len(new)}"]
        if all(isinstance(x, str) for x in old + new) and sorted(old) == sorted(new):
            return []  # the same names, in another order
        return [d for i, (a, b) in enumerate(zip(old, new)) for d in compare(a, b, f"{path}[{i}]", digits)]
    a, b = _number(old), _number(new)
    if isinstance(a, float) and isinstance(b, float) and not isinstance(old, bool):
        return [] if _same_number(a, b, digits) else [f"{path}: {old!r} against {new!r}"]
    return [] if old == new else [f"{path}: {old!r} against {new!r}"]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("old", type=Path)
    p.add_argument("new", type=Path)
    p.add_argument("--digits", type=int, default=DIGITS,
                   help=f"significant digits every number must share (default: {DIGITS})")
    args = p.parse_args(argv)
    if args.digits < 1:
        p.error("--digits must be 1 or more")
    diffs = compare(json.loads(args.old.read_text()), json.loads(args.new.read_text()), digits=args.digits)
    for line in diffs:
        print(line)
    print(f"{len(diffs)} difference(s) between {args.old} and {args.new} (numbers to {args.digits} significant "
          "digits)")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
