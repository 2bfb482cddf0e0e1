"""The throughput check's timing, measure_rates_interleaved: the engines alternate, each timed call follows
untimed ones of its own for the warm-up time, and the ratio is the median of the per-pair ratios (on a scripted
clock, so nothing here depends on timing)."""
import harness.warps.throughput as wc


class ScriptedClock:
    """perf_counter that advances only when a fake warp runs, by that warp's scripted seconds."""

    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now


def fake_warp(clock, calls, name, seconds):
    durations = iter(seconds)

    def run():
        calls.append(name)
        clock.now += next(durations)
    return run


def test_alternates_with_a_warm_up_before_each_timed_call(monkeypatch):
    clock, calls = ScriptedClock(), []
    monkeypatch.setattr(wc.time, "perf_counter", clock)
    tested = fake_warp(clock, calls, "tested", [9.0, 1.0] * 3)
    ref = fake_warp(clock, calls, "ref", [9.0, 2.0] * 3)
    tested_rate, ref_rate, ratio = wc.measure_rates_interleaved(tested, ref, n=100, pairs=3, warm=5.0)
    assert calls == ["tested", "tested", "ref", "ref"] * 3
    assert (tested_rate, ref_rate, ratio) == (100.0, 50.0, 2.0)  # the warm-up calls (9 s) are not counted


def test_the_warm_up_repeats_calls_until_its_time_has_passed(monkeypatch):
    clock, calls = ScriptedClock(), []
    monkeypatch.setattr(wc.time, "perf_counter", clock)
    tested = fake_warp(clock, calls, "tested", [1.0, 1.0, 1.0, 4.0])  # three warm-up calls fill 2.5 s, then the timed one
    ref = fake_warp(clock, calls, "ref", [3.0, 8.0])
    assert wc.measure_rates_interleaved(tested, ref, n=1, pairs=1, warm=2.5)[2] == 2.0
    assert calls == ["tested"] * 4 + ["ref"] * 2


def test_the_ratio_is_the_median_of_pairs_so_drift_cancels(monkeypatch):
    # The machine slows down tenfold in the middle pair: both engines alike, so that pair's ratio is still 2,
    # while the ratio of the two medians of times would not be.
    clock, calls = ScriptedClock(), []
    monkeypatch.setattr(wc.time, "perf_counter", clock)
    tested = fake_warp(clock, calls, "tested", [1.0, 1.0, 1.0, 10.0, 1.0, 1.5])
    ref = fake_warp(clock, calls, "ref", [1.0, 2.0, 1.0, 20.0, 1.0, 3.0])
    _, _, ratio = wc.measure_rates_interleaved(tested, ref, n=1, pairs=3, warm=1.0)
    assert ratio == 2.0


def test_a_slower_warp_reads_below_one(monkeypatch):
    clock, calls = ScriptedClock(), []
    monkeypatch.setattr(wc.time, "perf_counter", clock)
    tested = fake_warp(clock, calls, "tested", [1.0, 4.0] * 5)
    ref = fake_warp(clock, calls, "ref", [1.0, 1.0] * 5)
    assert wc.measure_rates_interleaved(tested, ref, n=1, pairs=5, warm=1.0)[2] == 0.25
