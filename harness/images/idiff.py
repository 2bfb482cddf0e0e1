"""What OpenImageIO's `idiff` would say of our mean image against the reference's mean image.

Reported beside our statistical verdict, never instead of it: idiff compares two single images with
fixed thresholds, so it fails a noisy-but-correct pair and passes a small uniform bias.
"""
from __future__ import annotations

import numpy as np

#: idiff's defaults: any pixel channel off by more than 1e-6 fails.
IDIFF_DEFAULT = {"fail": 1e-6, "warn": 1e-6, "failpercent": 0.0}
#: Test-suite style thresholds (`-fail 0.004 -failpercent 0.02 -warn 0.02`), the kind OIIO/OSL test
#: scripts pass to idiff for noisy outputs (not yet checked against OIIO's testsuite sources): fail
#: above 0.004 only if more than 0.02 % of pixels do; warn on any pixel above 0.02.
IDIFF_TESTSUITE = {"fail": 0.004, "warn": 0.02, "failpercent": 0.02}


def idiff(ours: np.ndarray, reference: np.ndarray, fail: float = IDIFF_TESTSUITE["fail"],
          warn: float = IDIFF_TESTSUITE["warn"], failpercent: float = IDIFF_TESTSUITE["failpercent"]) -> dict:
    """ImageBufAlgo.compare on two (H, W, C) images, with idiff's verdict rule.

    idiff: FAIL if more than `failpercent` % of pixels exceed `fail`; WARN if any pixel exceeds `warn`
    (or `fail`, within failpercent); else PASS.
    """
    import OpenImageIO as oiio

    if ours.shape != reference.shape:
        raise ValueError(f"idiff: shapes differ: {ours.shape} vs {reference.shape}")
    a = oiio.ImageBuf(np.ascontiguousarray(ours, dtype=np.float32))
    b = oiio.ImageBuf(np.ascontiguousarray(reference, dtype=np.float32))
    r = oiio.ImageBufAlgo.compare(a, b, fail, warn)
    npixels = ours.shape[0] * ours.shape[1]
    if r.nfail > failpercent / 100 * npixels:
        verdict = "FAIL"
    elif r.nwarn > 0 or r.nfail > 0:
        verdict = "WARN"
    else:
        verdict = "PASS"
    return {"verdict": verdict, "meanerror": r.meanerror, "rms_error": r.rms_error, "PSNR": r.PSNR,
            "maxerror": r.maxerror, "maxpixel": [r.maxx, r.maxy, r.maxc], "nfail": int(r.nfail),
            "nwarn": int(r.nwarn), "fail": fail, "warn": warn, "failpercent": failpercent}
