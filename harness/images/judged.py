"""What the image suite judged in a run, and why a selection holds no case at all: the tally a run's verdict is
made of (harness/verdict.py)."""
from __future__ import annotations

from collections.abc import Sequence

from harness.verdict import Tally

#: Cases named in a reason before "and N more".
SHOWN = 3


def _some(items: list[str]) -> str:
    more = f" and {len(items) - SHOWN} more" if len(items) > SHOWN else ""
    return ", ".join(items[:SHOWN]) + more


def why_no_cases(engine: str, integrators: Sequence[str] | None, not_applicable) -> str:
    """Why a selection of cases is empty, in one line: the engine renders no integrator the suite has an entry
    for, or its integrators apply to none of the scenes (`not_applicable`: (case, reason) pairs)."""
    from harness.images.suite import suite_integrators
    from harness.integrators import entries

    renders = suite_integrators(integrators)
    if not renders:
        listed = f" (it renders {', '.join(integrators)})" if integrators else ""
        return (f"the engine {engine} renders none of the integrators the suite has an entry for, "
                f"{', '.join(entries())}{listed}")
    if not_applicable:
        return (f"no case of the engine {engine} (it renders {', '.join(renders)}) applies to the scenes: "
                f"{_some([f'{c.key}: {why}' for c, why in not_applicable])}")
    return "no scene was selected"


def case_status(result) -> str:
    """An ImageResult as a verdict: "pass", "fail" (an error, a failed comparison) or "inconclusive" (nothing
    failed, and nothing could have)."""
    return result.verdict.lower()


def image_tally(results, not_applicable, no_cases: str = "") -> Tally:
    """The image cases of a run: passed, failed, and why the rest were not judged (not applicable to their
    scene, inconclusive), or `no_cases` when there were none."""
    statuses = [case_status(r) for r in results]
    reasons = []
    inconclusive = [r.case.key for r, s in zip(results, statuses) if s not in ("pass", "fail")]
    if inconclusive:
        reasons.append(f"{len(inconclusive)} inconclusive ({_some(inconclusive)})")
    if not_applicable:
        reasons.append(f"{len(not_applicable)} not applicable ({_some([f'{c.key}: {why}' for c, why in not_applicable])})")
    if not results and no_cases:
        reasons = [no_cases]
    return Tally("image cases", statuses.count("pass"), statuses.count("fail"), tuple(reasons))
