"""What OpenImageIO's `idiff` would say of the tested mean image against the reference's mean image.

Reported beside our statistical verdict, never instead of it: idiff compares two single images with
fixed thresholds and knows nothing of their noise, so it fails a noisy-but-correct pair and passes a
small bias hidden under its threshold (tests/comparison/test_idiff_real.py shows both on real renders).
"""
from __future__ import annotations

import numpy as np

#: The defaults of OpenImageIO's own test suite (testsuite/runtest.py: failthresh 0.004, failpercent
#: 0.02, hardfail 0.012, allowfailures 0), passed by its diff_command as
#: `idiff -a -fail 0.004 -failpercent 0.02 -hardfail 0.012 -allowfailures 0 -warn 0.008 -warnpercent 0.02`
#: (warn is 2 x failthresh). A pixel "fails" above 0.004; the pair fails if more than 0.02 % of pixels
#: do or any value is off by more than 0.012. Not the same as its neighbours: OSL's runtest.py uses
#: hardfail 0.01 and adds -failrelative 0.001; Blender's render tests (render_report.py) fail above
#: 0.016 on more than 1 % of pixels. runtest.py doubles all three under CI or DEBUG; we do not.
IDIFF_TESTSUITE = {"fail": 0.004, "failpercent": 0.02, "hardfail": 0.012, "warn": 0.008, "warnpercent": 0.02}


def idiff(tested: np.ndarray, reference: np.ndarray, thresholds: dict[str, float] = IDIFF_TESTSUITE) -> dict:
    """ImageBufAlgo.compare on two (H, W, C) images, with idiff's (OIIO 3.x) verdict rule: PASS if no
    pixel differs by more than `fail` in any channel (warnings alone never count); else FAIL if more
    than failpercent % of pixels do, or any value differs by more than `hardfail`; else WARN if more
    than warnpercent % of pixels differ by more than `warn`; else PASS."""
    import OpenImageIO as oiio

    if tested.shape != reference.shape:
        raise ValueError(f"idiff: shapes differ: {tested.shape} vs {reference.shape}")
    t = thresholds
    a = oiio.ImageBuf(np.ascontiguousarray(tested, dtype=np.float32))
    b = oiio.ImageBuf(np.ascontiguousarray(reference, dtype=np.float32))
    r = oiio.ImageBufAlgo.compare(a, b, t["fail"], t["warn"])
    npixels = tested.shape[0] * tested.shape[1]
    if r.nfail == 0:
        verdict = "PASS"
    elif r.nfail > t["failpercent"] / 100 * npixels or r.maxerror > t["hardfail"]:
        verdict = "FAIL"
    elif r.nwarn > t["warnpercent"] / 100 * npixels:
        verdict = "WARN"
    else:
        verdict = "PASS"
    return {"verdict": verdict, "meanerror": float(r.meanerror), "rms_error": float(r.rms_error),
            "PSNR": float(r.PSNR), "maxerror": float(r.maxerror), "maxpixel": [int(r.maxx), int(r.maxy), int(r.maxc)],
            "nfail": int(r.nfail), "nwarn": int(r.nwarn), "fail_percent_of_pixels": 100.0 * r.nfail / npixels,
            "thresholds": dict(t)}
