"""Error metrics between a test image and a reference (both (H, W, 3), linear RGB). Reported, not judged."""
from __future__ import annotations

import os

import numpy as np

# FLIP runs on OpenMP, whose threads otherwise spin on after each call: the render timed next met them
# still spinning and ran 20-70 % slower (cornell simple 128^2, 64 spp: 22 ms against 14 ms). Read
# when flip_evaluator loads OpenMP, so set before that; a value the user set is kept.
os.environ.setdefault("OMP_WAIT_POLICY", "passive")

#: Keeps relMSE finite where the reference is black (the usual 1e-2 of the literature).
RELMSE_EPSILON = 1e-2


def _tonemapped(img: np.ndarray, signed: bool) -> np.ndarray:
    """Display-referred [0,1] linear RGB: normals mapped from [-1,1], radiance clipped at 1."""
    return np.clip((img + 1.0) / 2.0 if signed else img, 0.0, 1.0)


def flip_map(test: np.ndarray, reference: np.ndarray, signed: bool = False) -> tuple[np.ndarray, float]:
    """FLIP error map (H, W) and its mean: HDR FLIP on radiance, LDR FLIP on mapped normals."""
    import flip_evaluator as flip

    if signed:
        ref, tst, mode = _tonemapped(reference, True), _tonemapped(test, True), "LDR"
    else:
        ref, tst, mode = np.clip(reference, 0, None), np.clip(test, 0, None), "HDR"
        # HDR-FLIP takes its exposures from the reference, so a common scale changes nothing; scaling
        # to a peak of 1 keeps them in range (flip_evaluator exits the process on a reference of 1e-30).
        peak = float(np.max(ref))
        if not (np.isfinite(peak) and peak > 0):
            return np.full(ref.shape[:2], np.nan), float("nan")
        ref, tst = ref / peak, tst / peak
    error, mean, _ = flip.evaluate(np.ascontiguousarray(ref, np.float32), np.ascontiguousarray(tst, np.float32),
                                   mode, inputsRGB=not signed, applyMagma=False)
    return np.asarray(error)[..., 0], float(mean)


#: SSIM's window side (scikit-image's default), and the smallest it is computed with on a small image.
SSIM_WINDOW, SSIM_SMALLEST_WINDOW = 7, 3


def _ssim(t: np.ndarray, r: np.ndarray, data_range: float) -> float:
    """SSIM with scikit-image's 7 x 7 window, narrowed to the largest odd side the image holds (a film 32 x 4
    is a real scene's shape at a small --resolution); NaN on an image under 3 pixels a side."""
    from skimage.metrics import structural_similarity

    shortest = min(t.shape[:2])
    side = min(SSIM_WINDOW, shortest if shortest % 2 else shortest - 1)
    if side < SSIM_SMALLEST_WINDOW:
        return float("nan")
    return float(structural_similarity(t, r, channel_axis=-1, data_range=data_range, win_size=side))


def image_metrics(test: np.ndarray, reference: np.ndarray, signed: bool = False,
                  maps: dict[str, np.ndarray] | None = None) -> dict[str, float]:
    """MSE, RMSE, relMSE, SMAPE, PSNR, SSIM, FLIP mean and 95th percentile, CIEDE2000 mean, mean ratio.

    `signed` marks images with negative values (normals): FLIP and CIEDE2000 then
    see (x + 1) / 2. `maps`, if given, receives the FLIP map as "flip" (FLIP costs more than the rest).
    """
    import colour

    t = np.asarray(test, np.float64)
    r = np.asarray(reference, np.float64)
    diff = t - r
    mse = float(np.mean(diff**2))
    peak = float(np.max(np.abs(r))) or 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        smape_terms = np.where(np.abs(t) + np.abs(r) > 0, 2 * np.abs(diff) / (np.abs(t) + np.abs(r)), 0.0)
    data_range = float(r.max() - r.min()) or 1.0
    ssim = _ssim(t, r, data_range)
    error, flip_mean = flip_map(test, reference, signed)
    if maps is not None:
        maps["flip"] = error
    lab = [colour.XYZ_to_Lab(colour.sRGB_to_XYZ(_tonemapped(x, signed), apply_cctf_decoding=False)) for x in (t, r)]
    ciede = float(np.mean(colour.delta_E(lab[0], lab[1], method="CIE 2000")))
    ref_mean = float(np.mean(r))
    return {
        "mse": mse,
        "rmse": float(np.sqrt(mse)),
        "relmse": float(np.mean(diff**2 / (r**2 + RELMSE_EPSILON))),
        "smape": float(np.mean(smape_terms)),
        "psnr": float(10 * np.log10(peak**2 / mse)) if mse > 0 else float("inf"),
        "ssim": ssim,
        "flip_mean": flip_mean,
        "flip_p95": float(np.percentile(error, 95)),
        "ciede2000_mean": ciede,
        "mean_ratio": float(np.mean(t)) / ref_mean if ref_mean != 0 else float("nan"),
    }
