"""pyrender's `path`: a path tracer as Mitsuba 3's `path` defines it.

At each vertex, one light sample (next-event estimation) and one cosine-weighted BSDF sample that continues the
path, the two combined by multiple importance sampling with the power heuristic; the emission a BSDF sample
reaches is weighted against the light sample that could have found it. `max_depth` counts vertices as Mitsuba
does (1: the emitters seen, 2: direct light, -1: no limit); from the `rr_depth`-th bounce on, Russian roulette
ends a path with probability 1 - min(max throughput, 0.95) and divides the survivors by the rest. Surfaces are
Mitsuba's `diffuse`, one-sided about the shading normal. Its lights and ray tracing are direct's
(pyrender_direct.py); each loop runs over every path still alive, in numpy.
"""
import math
from dataclasses import dataclass

import numpy as np

from pyrender_direct import cosine_hemisphere, emitted, hide_emitters, light_sample, power_heuristic
from pyrender_lights import dot

#: Russian roulette's highest survival probability (Mitsuba's), so that a path of full throughput ends too.
MAX_SURVIVAL = 0.95


@dataclass(frozen=True)
class PathSettings:
    """Mitsuba's `path` parameters, with its defaults."""

    max_depth: int = -1
    rr_depth: int = 5
    hide_emitters: bool = False


def path_settings(integrator):
    """The parameters of an <integrator> element (None: none) as Mitsuba's `path` reads them; ValueError for a
    bad value."""
    values = {"max_depth": -1, "rr_depth": 5, "hide_emitters": False}
    for el in [] if integrator is None else integrator:
        name, value = el.get("name"), el.get("value", "").strip()
        if el.tag == "integer" and name in ("max_depth", "rr_depth"):
            try:
                values[name] = int(value)
            except ValueError:
                raise ValueError(f"<integer name={name!r}> is {value!r}, not an integer") from None
            if values[name] < (-1 if name == "max_depth" else 1):
                raise ValueError(f"<integer name={name!r}> is {value}: max_depth is at least -1, rr_depth at least 1")
        elif el.tag == "boolean" and name == "hide_emitters":
            values[name] = hide_emitters(value)
    return PathSettings(**values)


def path(tracer, lights, ray_o, ray_d, hits, rng, settings, bug=None):
    """The radiance of each camera ray (3, n): `ray_o`, `ray_d` their origins and directions, `hits` what they
    found. `bug` "path-rr" plants Russian roulette that does not divide the survivors by their probability."""
    n = ray_d.shape[1]
    result, throughput = np.zeros((3, n)), np.ones((3, n))
    if settings.max_depth == 0:
        return result
    if not settings.hide_emitters:
        for _, radiance in emitted(lights, ray_o, hits, ray_d):
            result += radiance
    pick = 1 / len(lights)  # the chance of each light: uniform, Mitsuba's default
    alive, d_in, depth = np.ones(n, dtype=bool), ray_d, 0
    while settings.max_depth < 0 or depth + 1 < settings.max_depth:
        # One-sided: a surface seen from behind its shading normal reflects nothing, and the path ends there.
        active = alive & hits.valid & (dot(hits.sh_n, -d_in) > 0)
        if not active.any():
            break
        # The light sample.
        which = np.minimum((rng.random(n) * len(lights)).astype(int), len(lights) - 1)
        d, dist, radiance, pdf, delta = light_sample(lights, which, hits.p, rng.random((2, n)))
        cos = dot(hits.sh_n, d)
        value = np.where(pdf > 0, radiance / np.where(pdf > 0, pdf * pick, 1), 0.0)
        weight = np.where(delta, 1.0, power_heuristic(pdf * pick, np.maximum(cos, 0) / math.pi))
        seen = tracer.visible(hits, d, dist, active & (cos > 0) & (pdf > 0))
        result += np.where(seen, throughput * hits.rho / math.pi * np.maximum(cos, 0) * value * weight, 0.0)
        # The BSDF sample that continues the path: its weight f cos / pdf is rho.
        d, cos = cosine_hemisphere(hits, rng.random((2, n)))
        throughput = np.where(active, throughput * hits.rho, 0.0)
        found = tracer.trace(hits, d, active)
        for light_pdf, radiance in emitted(lights, hits.p, found, d):
            result += np.where(active, throughput * radiance * power_heuristic(cos / math.pi, light_pdf * pick), 0.0)
        depth += 1
        if depth >= settings.rr_depth:
            survival = np.minimum(throughput.max(axis=0), MAX_SURVIVAL)
            survives = rng.random(n) < survival
            if bug != "path-rr":
                throughput = throughput / np.where(survives, survival, 1.0)
            active &= survives
        alive, hits, d_in = active & (throughput.max(axis=0) > 0), found, d
    return result
