"""JUnit XML, so CI systems show one test case per warp and per (scene, integrator)."""
from __future__ import annotations

import xml.etree.ElementTree as ET

from harness.images.result import ImageResult


def _warp_case(w: dict) -> str:
    return w["warp"] + (f" {w['params']}" if w["params"] else "")


def _warnings(w: dict) -> str:
    """The WARN findings of a warp's checks (from results.json), one per line; "" when there are none."""
    return "\n".join(f"{k}: {f['text']}" for k, c in w["checks"].items() if c.get("verdict") == "WARN"
                     for f in c.get("findings", []) if f["severity"] == "WARN")


def junit_xml(images: list[ImageResult], warps: list[dict] | None, meta: dict | None = None) -> str:
    """A <testsuites> document: suite "warps" (if given) and one suite per integrator, each with the run's
    `meta` (the engines' names, versions, files and commands) as its <properties>."""
    root = ET.Element("testsuites", name="mcval")

    def suite(name: str, cases: list[tuple[str, bool | None, str, float]], notes: dict[str, str] | None = None) -> None:
        """One <testsuite>; `notes` (by case name) become a passing case's <system-out>, e.g. its warnings. A
        case whose `ok` is None was not judged (INCONCLUSIVE): a <skipped> with the reason."""
        el = ET.SubElement(root, "testsuite", name=name, tests=str(len(cases)),
                           failures=str(sum(ok is False for _, ok, _, _ in cases)),
                           skipped=str(sum(ok is None for _, ok, _, _ in cases)))
        if meta:
            properties = ET.SubElement(el, "properties")
            for key, value in meta.items():
                ET.SubElement(properties, "property", name=key, value=str(value))
        for case_name, ok, message, seconds in cases:
            tc = ET.SubElement(el, "testcase", classname=f"mcval.{name}", name=case_name, time=f"{seconds:.3f}")
            if ok is None:
                ET.SubElement(tc, "skipped", message=message.split("\n", 1)[0]).text = message
            elif not ok:
                # The attribute holds the first line (a failed render's reason); the text all of it.
                ET.SubElement(tc, "failure", message=message.split("\n", 1)[0]).text = message
            elif (notes or {}).get(case_name):
                ET.SubElement(tc, "system-out").text = notes[case_name]

    if warps is not None:
        suite("warps", [(_warp_case(w), w["pass"],
                         w.get("failure") or "; ".join(f"{k}: {c['summary']}" for k, c in w["checks"].items()
                                                       if c["pass"] is False),
                         w["seconds"]) for w in warps],
              {_warp_case(w): _warnings(w) for w in warps})
    for integrator in sorted({r.case.integrator for r in images}):
        cases = []
        for r in (r for r in images if r.case.integrator == integrator):
            message = r.failures
            if r.error is not None:
                message = r.error + (f"\n{r.error_output}" if r.error_output else "")
            if r.verdict == "INCONCLUSIVE":
                message = f"INCONCLUSIVE: {r.inconclusive}"
            ok = None if r.verdict == "INCONCLUSIVE" else r.passed
            cases.append((r.case.scene, ok, (r.note + "; " if r.note else "") + message,
                          r.tested.seconds.get("total", 0.0) if r.tested else 0.0))
        suite(integrator, cases)
    return ET.tostring(root, encoding="unicode", xml_declaration=True)
