"""What changed since an earlier run: verdicts, image means and times, flagged only beyond noise."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

#: A change of the image mean is flagged beyond this many standard errors (both runs' combined).
MEAN_SIGMAS = 4.0
#: A time is flagged when it changes by more than this factor and by more than TIME_FLOOR seconds:
#: machines are shared and noisy, and a render of a tenth of a second is mostly process start-up,
#: which varies by that much from one run to the next.
TIME_FACTOR = 1.5
TIME_FLOOR = 0.25


def load_baseline(path: Path) -> dict | None:
    """The results.json of an earlier run, or None if there is none or it has no images."""
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return data if data.get("images") else None


def compare_runs(current: list[dict], baseline: dict) -> list[dict]:
    """Per (integrator, scene) of the current run: the flags raised against the baseline."""
    before = {(e["integrator"], e["scene"]): e for e in baseline["images"]}
    out = []
    for e in current:
        old = before.get((e["integrator"], e["scene"]))
        flags = []
        if old is None:
            flags.append("new case")
        else:
            was, now = _verdict(old), _verdict(e)
            if was != now:
                flags.append(f"verdict {was} -> {now}")
            if e.get("error") and e["error"] != old.get("error"):
                flags.append(f"render failed: {e['error']}")
            if "image_mean" not in old or "image_mean" not in e:  # a render failed: nothing to measure
                out.append(_entry(e, old, flags))
                continue
            # dtype=float: results.json holds a NaN or Inf as the string "nan" or "inf".
            m0, m1 = np.array(old["image_mean"], dtype=float), np.array(e["image_mean"], dtype=float)
            se = np.hypot(np.array(old["image_mean_se"], dtype=float), np.array(e["image_mean_se"], dtype=float))
            z = np.abs(m1 - m0) / np.maximum(se, 1e-12)
            if np.any(z > MEAN_SIGMAS) and np.any(m1 != m0):
                flags.append(f"image mean moved {float(np.max(z)):.1f} standard errors "
                             f"({float(np.mean(m1) / max(np.mean(m0), 1e-12)) - 1:+.2%})")
            tested = e.get("engine")  # the tested engine's time, where the earlier run timed the same engine
            if tested in old["seconds"] and tested in e["seconds"]:
                t0, t1 = old["seconds"][tested]["total"], e["seconds"][tested]["total"]
                if abs(t1 - t0) > TIME_FLOOR and not (1 / TIME_FACTOR < t1 / max(t0, 1e-9) < TIME_FACTOR):
                    flags.append(f"time {t0:.2f}s -> {t1:.2f}s")
        out.append(_entry(e, old, flags))
    return out


def _entry(e: dict, old: dict | None, flags: list[str]) -> dict:
    return {"integrator": e["integrator"], "scene": e["scene"], "flags": flags,
            "relmse_before": None if old is None else old["metrics"].get("relmse"),
            "relmse_now": e["metrics"].get("relmse")}


def _verdict(entry: dict) -> str:
    """PASS, FAIL or INCONCLUSIVE (results.json of runs that gave no verdict word: from `pass`)."""
    return entry.get("verdict") or ("PASS" if entry["pass"] else "FAIL")
