"""A warp's throughput: samples per second, the tested engine's beside the reference's, timed in alternation."""
from __future__ import annotations

import time
from typing import Any, Callable

import numpy as np

from harness.engines.base import WarpFunctions
from harness.warps.check_result import CheckResult
from harness.warps.checks import Sampler

#: Below this many samples per second a warp cannot feed a renderer (a per-sample Python loop, a stuck rejection).
THROUGHPUT_FLOOR = 1e6
#: Samples a call when a warp is timed as Python functions: vectorised code runs at its full rate by then, and a
#: per-sample loop is told from it without spending seconds a call.
PYTHON_CALL_SAMPLES = 1 << 18


def throughput_check(sample: Sampler, native_run, reference: WarpFunctions | None,
                     n: int = 1 << 20, judged: bool = True) -> CheckResult:
    """Samples per second of our warp, beside the reference's (each in its own containers).

    Passes above THROUGHPUT_FLOOR if `judged` (else it always passes: a user's code is timed, not judged);
    the comparison with the reference is reported, not judged (speed goals live in bench/).
    """
    if native_run is None:
        n = min(n, PYTHON_CALL_SAMPLES)
        u = np.random.default_rng(1).random((n, 2))
        tested = lambda: sample(u)  # noqa: E731
    else:
        tested = native_run(n)
    if reference is None:
        rate = measure_rate(tested, n)
    else:
        # Interleaved, the tested engine's then the reference's, the ratio taken per pair: on a shared machine
        # back-to-back medians of one engine and then the other swing with the load.
        rate, ref_rate, ratio = measure_rates_interleaved(tested, reference.native_run(n), n)
    details: dict[str, Any] = {"samples_per_second": rate}
    summary = f"{rate / 1e6:.0f} M/s"
    if reference is not None:
        details.update(reference_samples_per_second=ref_rate, ratio=ratio, method="interleaved pairs, median ratio")
        summary += f" ({ratio:.2f}x Mitsuba)"
    details["floor"] = THROUGHPUT_FLOOR if judged else None
    if not judged:
        summary += " (reported, not judged)"
    return CheckResult(bool(rate >= THROUGHPUT_FLOOR or not judged), rate, summary, details=details)


#: Seconds each engine warms up before a timed call: its thread pool and the cores reach their steady rate only
#: after some milliseconds of work (one untimed call was not enough: a call read half its rate after a pause), and
#: Mitsuba's pool spins for some 30 ms after a call, so a shorter warm-up would time the tested engine on one core.
WARM_SECONDS = 0.03


def _warm_up(call: Callable[[], Any], seconds: float) -> None:
    """Calls `call` at least once and until `seconds` have passed."""
    end = time.perf_counter() + seconds
    call()
    while time.perf_counter() < end:
        call()


def measure_rates_interleaved(tested: Callable[[], Any], reference: Callable[[], Any], n: int,
                              pairs: int = 5, warm: float = WARM_SECONDS) -> tuple[float, float, float]:
    """Samples per second of two calls that warp n samples each, timed in alternation (tested, reference, tested,
    ...), each timed call straight after `warm` seconds of untimed calls of its own (its threads awake and
    the other's quiet, its arrays cached): the median rate of each, and the median over the pairs of the tested
    call's rate over the reference's, in which the machine's drift between the two runs of a pair cancels."""
    t_tested, t_ref = [], []
    for _ in range(pairs):
        for call, times in ((tested, t_tested), (reference, t_ref)):
            _warm_up(call, warm)
            start = time.perf_counter()
            call()
            times.append(time.perf_counter() - start)
    ratios = np.array(t_ref) / np.array(t_tested)
    return n / float(np.median(t_tested)), n / float(np.median(t_ref)), float(np.median(ratios))


def measure_rate(sample: Callable[[], Any], n: int, repeats: int = 5) -> float:
    """Samples per second of a call that warps n samples: the median of several runs after a warm-up."""
    sample()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        sample()
        times.append(time.perf_counter() - start)
    return n / float(np.median(times))
