"""harness.comparison.idiff against hand figures and against OpenImageIO's own idiff binary."""
import subprocess
from pathlib import Path

import numpy as np
import pytest

from harness.comparison.idiff import IDIFF_TESTSUITE, idiff


def test_figures_match_hand_computation():
    a = np.zeros((2, 3, 3), np.float32)
    b = a.copy()
    b[0, 0, 0] = 0.5
    r = idiff(a, b)
    assert r["maxerror"] == pytest.approx(0.5)
    assert r["meanerror"] == pytest.approx(0.5 / 18)
    assert r["rms_error"] == pytest.approx(np.sqrt(0.25 / 18))
    assert r["nfail"] == 1 and r["verdict"] == "FAIL"
    assert r["fail_percent_of_pixels"] == pytest.approx(100 / 6)
    assert idiff(a, a)["verdict"] == "PASS"


def test_few_failures_pass_below_hardfail_and_fail_above():
    a = np.zeros((100, 100, 3), np.float32)
    b = a.copy()
    b[0, 0, 0] = 0.01  # 1 pixel of 10^4 = 0.01 % < 0.02 %, under hardfail 0.012
    assert idiff(a, b)["verdict"] == "PASS"
    b[0, 0, 0] = 0.02  # one value beyond hardfail fails the image
    assert idiff(a, b)["verdict"] == "FAIL"
    b[0, 0, 0] = 0.0
    b[:2, :2, 1] = 0.006  # 4 pixels (0.04 %) over fail 0.004, none over warn 0.008
    assert idiff(a, b)["verdict"] == "FAIL"
    b[:2, :2, 1] = 0.0
    b[0, :3, 2] = 0.003  # under fail: nothing counted
    assert idiff(a, b)["verdict"] == "PASS"


def _binary() -> Path | None:
    import OpenImageIO
    path = Path(OpenImageIO.__file__).parent / "bin" / "idiff"
    return path if path.exists() else None


def _write(path: Path, image: np.ndarray) -> None:
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(np.ascontiguousarray(image, np.float32))
    assert buf.write(str(path)), buf.geterror()


#: idiff warns only when some pixel fails but too few to fail the image, and more than warnpercent
#: warn; warn below fail reaches that branch.
WARN_BELOW_FAIL = {"fail": 0.01, "failpercent": 0.1, "hardfail": 0.05, "warn": 0.002, "warnpercent": 0.02}


@pytest.mark.parametrize("case, expected", [("pass", "PASS"), ("warnings_only", "PASS"), ("warn", "WARN"),
                                            ("fail_percent", "FAIL"), ("hardfail", "FAIL")])
def test_verdict_matches_the_idiff_binary(tmp_path, case, expected):
    """The same verdict as `idiff -fail F -failpercent P -hardfail H -warn W -warnpercent P` on EXR files."""
    binary = _binary()
    assert binary is not None, "the openimageio wheel ships bin/idiff"
    rng = np.random.default_rng(5)
    a = rng.random((64, 64, 3), dtype=np.float32)
    b = a.copy()
    t = IDIFF_TESTSUITE
    if case == "pass":
        b[0, 0, 0] += 0.001                 # under every threshold
    elif case == "warnings_only":
        t = WARN_BELOW_FAIL
        b[:3, 0, 2] += 0.004                # warnings without a single failing pixel: idiff passes
    elif case == "warn":
        t = WARN_BELOW_FAIL
        b[0, 5, 0] += 0.011                 # 1 of 4096 pixels over fail: under failpercent 0.1 % (4 pixels)
        b[:3, 0, 2] += 0.004                # 4 pixels (0.1 %) over warn: more than warnpercent 0.02 %
    elif case == "fail_percent":
        b[:2, :2, 1] += 0.006               # 4 pixels (0.1 %) over fail 0.004, under hardfail
    elif case == "hardfail":
        b[7, 7, 2] += 0.05                  # one value beyond hardfail 0.012
    _write(tmp_path / "a.exr", a)
    _write(tmp_path / "b.exr", b)
    cmd = [str(binary), "-fail", str(t["fail"]), "-failpercent", str(t["failpercent"]), "-hardfail", str(t["hardfail"]),
           "-warn", str(t["warn"]), "-warnpercent", str(t["warnpercent"]), str(tmp_path / "a.exr"), str(tmp_path / "b.exr")]
    res = subprocess.run(cmd, capture_output=True, text=True)
    theirs = {0: "PASS", 1: "WARN", 2: "FAIL"}[res.returncode]
    mcval = idiff(a, b, t)["verdict"]
    assert mcval == theirs, res.stdout
    assert mcval == expected
