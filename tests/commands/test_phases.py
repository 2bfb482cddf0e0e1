"""Phases: each phase's wall seconds in order, the start-up first, summed into the total and the one-line
summary; the time since the process started is positive and grows."""
import time

from harness.commands.phases import Phases, seconds_since_process_start


def test_phases_are_timed_in_order_after_the_start_up():
    phases = Phases()
    with phases.timed("warps"):
        time.sleep(0.02)
    with phases.timed("images"):
        pass
    assert list(phases.seconds) == ["start-up", "warps", "images"]
    assert phases.seconds["warps"] >= 0.02
    assert phases.total() == round(sum(phases.seconds.values()), 2)
    assert phases.line().startswith("start-up ") and "warps" in phases.line() and phases.line().endswith(" s")


def test_a_phase_that_raises_is_still_timed():
    phases = Phases()
    try:
        with phases.timed("invariances"):
            raise RuntimeError("a render failed")
    except RuntimeError:
        pass
    assert "invariances" in phases.seconds


def test_the_process_start_is_in_the_past():
    first = seconds_since_process_start()
    time.sleep(0.01)
    assert 0 < first < seconds_since_process_start()
