"""How fast each of our samplers converges on a small case: the slope of log MSE against log spp, the MSE taken
against our own high-sample image and averaged over seeds. Independent samples give -1 (MSE ~ 1/N); a stratified
sampler gives a steeper slope. tests/bench/test_sampler_slopes.py bounds these slopes; the bench reports them."""
from __future__ import annotations

import numpy as np

from harness.images.suite import SCENES_DIR

#: Samples per pixel of the steps, seeds per step, the reference's samples (in two renders) and the film side.
SPP = (4, 8, 16, 32, 64, 128)
SEEDS = 6
REFERENCE_SPP = 4096
RESOLUTION = 32
#: What the test asks: independent within -1 +- 0.15; sobol steeper than this.
INDEPENDENT_BOUNDS = (-1.15, -0.85)
SOBOL_BELOW = -1.15


def _image(module, scene: str, integrator: str, spp: int, seed: int, sampler: str) -> np.ndarray:
    return module.render(scene, spp=spp, seed=seed, integrator=integrator, params={"res": str(RESOLUTION)},
                         sampler=sampler)["mean"].astype(np.float64)


def mse_slope(scene: str, integrator: str, sampler: str, reference: np.ndarray | None = None) -> float:
    """The slope of log MSE against log spp for `sampler`, with the deterministic seeds 10 spp + k."""
    from harness.native import renderer_module
    module = renderer_module()
    if reference is None:
        reference = our_reference(scene, integrator)
    mse = [np.mean([np.mean((_image(module, scene, integrator, s, 10 * s + k, sampler) - reference) ** 2)
                    for k in range(SEEDS)]) for s in SPP]
    return float(np.polyfit(np.log(SPP), np.log(mse), 1)[0])


def our_reference(scene: str, integrator: str) -> np.ndarray:
    """Our own image of 2 x REFERENCE_SPP sobol samples, far below the steps' error (seeds apart from theirs)."""
    from harness.native import renderer_module
    module = renderer_module()
    return np.mean([_image(module, scene, integrator, REFERENCE_SPP, 1000 + k, "sobol") for k in range(2)], axis=0)


def sampler_slopes(scene: str = "cornell", integrators=("simple", "ao"),
                   samplers=("independent", "sobol")) -> dict:
    """Every sampler's slope on `scene` with each integrator, and the setting, for results.json."""
    path = str(SCENES_DIR / f"{scene}.xml")
    slopes = {}
    for integrator in integrators:
        reference = our_reference(path, integrator)
        slopes[integrator] = {s: mse_slope(path, integrator, s, reference) for s in samplers}
    return {"scene": scene, "resolution": RESOLUTION, "spp": list(SPP), "seeds": SEEDS,
            "reference_spp": 2 * REFERENCE_SPP, "slopes": slopes,
            "expected": {"independent": list(INDEPENDENT_BOUNDS), "sobol": f"< {SOBOL_BELOW}"}}
