"""How fast each sampler of the tested engine converges on a small case: the slope of log MSE against log spp, the
MSE taken against the engine's own high-sample image and averaged over seeds. Independent samples give -1
(MSE ~ 1/N); a stratified sampler gives a steeper slope. tests/bench/test_sampler_slopes.py bounds these slopes;
the bench reports them."""
from __future__ import annotations

import numpy as np

from harness.engines.base import Engine
from harness.images.suite import SCENES_DIR

#: Samples per pixel of the steps, seeds per step, the reference's samples (in two renders) and the film side.
SPP = (4, 8, 16, 32, 64, 128)
SEEDS = 6
REFERENCE_SPP = 4096
RESOLUTION = 32
#: What the test asks: independent within -1 +- 0.15; sobol steeper than this.
INDEPENDENT_BOUNDS = (-1.15, -0.85)
SOBOL_BELOW = -1.15


def _image(engine: Engine, scene: str, integrator: str, spp: int, seed: int) -> np.ndarray:
    return engine.render(scene, integrator, spp, 1, seed, {"res": str(RESOLUTION)}).mean.astype(np.float64)


def mse_slope(engine: Engine, scene: str, integrator: str, reference: np.ndarray) -> float:
    """The slope of log MSE against log spp of `engine` (made with the sampler to measure), with the
    deterministic seeds 10 spp + k."""
    mse = [np.mean([np.mean((_image(engine, scene, integrator, s, 10 * s + k) - reference) ** 2)
                    for k in range(SEEDS)]) for s in SPP]
    return float(np.polyfit(np.log(SPP), np.log(mse), 1)[0])


def own_reference(engine: Engine, scene: str, integrator: str) -> np.ndarray:
    """The engine's own image of 2 x REFERENCE_SPP samples (made with its best sampler), far below the steps'
    error (seeds apart from theirs)."""
    return np.mean([_image(engine, scene, integrator, REFERENCE_SPP, 1000 + k) for k in range(2)], axis=0)


def sampler_slopes(engines: dict[str, Engine], scene: str = "cornell", integrators=("simple", "ao")) -> dict:
    """The slope of each sampler's engine (`engines`: sampler name -> the tested engine made with it; the last
    one also renders the reference image) on `scene` with each integrator, and the setting, for results.json."""
    path = str(SCENES_DIR / f"{scene}.xml")
    slopes = {}
    for integrator in integrators:
        reference = own_reference(list(engines.values())[-1], path, integrator)
        slopes[integrator] = {s: mse_slope(e, path, integrator, reference) for s, e in engines.items()}
    return {"scene": scene, "resolution": RESOLUTION, "spp": list(SPP), "seeds": SEEDS,
            "reference_spp": 2 * REFERENCE_SPP, "slopes": slopes,
            "expected": {"independent": list(INDEPENDENT_BOUNDS), "sobol": f"< {SOBOL_BELOW}"}}
