"""idiff's verdict in words, for the terminal table and the HTML report."""
from __future__ import annotations

from harness.comparison.idiff import IDIFF_TESTSUITE

LEGEND = (f"idiff: OpenImageIO's image diff at its test suite's thresholds (fail {IDIFF_TESTSUITE['fail']:g} "
          f"on more than {IDIFF_TESTSUITE['failpercent']:g} % of pixels or any value off by "
          f"{IDIFF_TESTSUITE['hardfail']:g}; warn {IDIFF_TESTSUITE['warn']:g}) on the two mean images. It knows "
          "nothing of noise: shown for comparison, it decides nothing")


def idiff_short(result: dict) -> str:
    """E.g. "FAIL 3.2%": the verdict and the share of pixels over `fail` (the figures are in the report)."""
    if result.get("verdict") == "n/a":
        return "n/a"
    return f"{result['verdict']} {result['fail_percent_of_pixels']:.2g}%"


def idiff_sentence(result: dict) -> str:
    """One line for the report: the verdict and its figures, or why there is none."""
    if result.get("verdict") == "n/a":
        return f"idiff: n/a ({result.get('reason')})"
    return (f"idiff: {result['verdict']}: largest error {result['maxerror']:.3g}, "
            f"{result['fail_percent_of_pixels']:.3g} % of pixels over {result['thresholds']['fail']:g}, "
            f"mean error {result['meanerror']:.3g}")
