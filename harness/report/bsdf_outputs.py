"""The BSDF matrix for people and CI: a terminal table (BSDF x angle, a verdict per check) and JUnit XML (one case
per BSDF and angle)."""
from __future__ import annotations

import xml.etree.ElementTree as ET

from rich.table import Table

from harness.bsdfs.evaluate import ALL_CHECKS
from harness.bsdfs.suite import BsdfRow
from harness.report.warp_table import verdict_text


def bsdf_table(rows: list[BsdfRow], level: float) -> Table:
    """One row per BSDF and angle, one column per check: its verdict ("-": not run, no such plugin in Mitsuba)."""
    table = Table(title=f"BSDF matrix (per-test level {level:.2g}, Sidak over the run)", header_style="bold")
    for column in ("BSDF", "theta", *ALL_CHECKS):
        table.add_column(column)
    for row in rows:
        if row.failure:  # no check ran: the FAIL line under the table says why
            table.add_row(row.label, "" if row.theta is None else f"{row.theta:g}", "[red]not checked[/]",
                          *[""] * (len(ALL_CHECKS) - 1))
            continue
        table.add_row(row.label, f"{row.theta:g}",
                      *(verdict_text(row.checks[k].passed) if k in row.checks else "-" for k in ALL_CHECKS))
    return table


def bsdf_junit(rows: list[BsdfRow], meta: dict) -> str:
    root = ET.Element("testsuites", name="mcval")
    suite = ET.SubElement(root, "testsuite", name="bsdfs", tests=str(len(rows)),
                          failures=str(sum(not r.passed for r in rows)), skipped="0")
    properties = ET.SubElement(suite, "properties")
    for key, value in meta.items():
        ET.SubElement(properties, "property", name=key, value=str(value))
    for row in rows:
        name = row.label if row.theta is None else f"{row.label} at {row.theta:g} degrees"
        case = ET.SubElement(suite, "testcase", classname="mcval.bsdfs", name=name, time=f"{row.seconds:.3f}")
        if not row.passed:
            message = row.failure or "; ".join(f"{k}: {c.summary}" for k, c in row.checks.items() if not c.passed)
            ET.SubElement(case, "failure", message=message).text = message
    return ET.tostring(root, encoding="unicode")
