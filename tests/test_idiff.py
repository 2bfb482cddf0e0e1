import numpy as np
import pytest

from harness.images.idiff import IDIFF_DEFAULT, idiff


def test_figures_match_hand_computation():
    a = np.zeros((2, 3, 3), np.float32)
    b = a.copy()
    b[0, 0, 0] = 0.5
    r = idiff(a, b, **IDIFF_DEFAULT)
    assert r["maxerror"] == pytest.approx(0.5)
    assert r["meanerror"] == pytest.approx(0.5 / 18)
    assert r["rms_error"] == pytest.approx(np.sqrt(0.25 / 18))
    assert r["nfail"] == 1 and r["verdict"] == "FAIL"
    assert idiff(a, a)["verdict"] == "PASS"


def test_failpercent_turns_a_few_failures_into_a_warning():
    a = np.zeros((100, 100, 3), np.float32)
    b = a.copy()
    b[0, 0, 0] = 1.0  # 1 pixel of 10^4 = 0.01 % < 0.02 %
    assert idiff(a, b)["verdict"] == "WARN"
