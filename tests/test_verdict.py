"""A run PASSes only when nothing failed and each suite judged something; one that judged nothing says why."""
from harness.verdict import Tally, Verdict, run_verdict


def test_judged_and_not_failed_passes():
    assert run_verdict([Tally("image cases", passed=3, not_judged=("1 not applicable",))]) == (Verdict.PASS, "")


def test_a_failure_fails_whatever_else():
    assert run_verdict([Tally("warps", passed=5, failed=1)])[0] is Verdict.FAIL
    assert run_verdict([Tally("warps", passed=5)], ok=False)[0] is Verdict.FAIL
    assert run_verdict([Tally("image cases", not_judged=("all 0",)), Tally("warps", failed=1)])[0] is Verdict.FAIL


def test_nothing_judged_is_no_pass_and_names_each_empty_suite():
    verdict, reason = run_verdict([Tally("warps", passed=2), Tally("image cases", not_judged=("2 inconclusive",)),
                                   Tally("invariance cells of black")])
    assert verdict is Verdict.NOTHING_JUDGED
    assert reason == "nothing was judged: image cases: 2 inconclusive; no invariance cells of black ran"
    assert run_verdict([]) == (Verdict.NOTHING_JUDGED, "nothing was judged: no suite ran")
