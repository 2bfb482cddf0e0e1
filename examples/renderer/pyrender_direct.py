"""pyrender's `direct`: light from every emitter at the first hit, as Mitsuba 3's `direct` defines it.

`emitter_samples` light samples and `bsdf_samples` cosine-weighted BSDF samples per camera ray, combined by
multiple importance sampling with the power heuristic (each density scaled by its strategy's share of the
samples, as Mitsuba does); a light is picked uniformly among the scene's emitters. Camera rays see the
emitters they reach unless `hide_emitters`. Surfaces are Mitsuba's `diffuse`: rho/pi * cos, one-sided about
the shading normal. Mitsuba traces the rays; the rest is numpy on arrays of shape (3, n).
"""
import math
from dataclasses import dataclass

import numpy as np

from pyrender_lights import dot


@dataclass(frozen=True)
class DirectSettings:
    """Mitsuba's `direct` parameters, with its defaults."""

    emitter_samples: int = 1
    bsdf_samples: int = 1
    hide_emitters: bool = False


@dataclass(frozen=True)
class Hits:
    """What a batch of rays found, in numpy: `valid`, point `p`, geometric and shading normals `n`, `sh_s`,
    `sh_t`, `sh_n`, distance `t`, the hit shape's id (Mitsuba's registry index) and the reflectance `rho`."""

    valid: np.ndarray
    p: np.ndarray
    n: np.ndarray
    sh_s: np.ndarray
    sh_t: np.ndarray
    sh_n: np.ndarray
    t: np.ndarray
    shape: np.ndarray
    rho: np.ndarray

    @classmethod
    def of(cls, si, mi, dr):
        frame, valid = si.sh_frame, si.is_valid()
        values = [valid, si.p, si.n, frame.s, frame.t, frame.n, si.t, dr.reinterpret_array(mi.UInt32, si.shape),
                  si.bsdf().eval_diffuse_reflectance(si, valid)]
        dr.eval(*values)  # one kernel for all of them, not one per conversion
        kinds = (bool, *[np.float64] * 6, None, np.float64)
        valid, p, n, sh_s, sh_t, sh_n, t, shape, rho = (np.array(v, dtype=kind) for v, kind in zip(values, kinds))
        # A miss has t = inf and p far away: 0 instead (no ray leaves it, and no arithmetic overflows).
        return cls(valid, np.where(valid, p, 0.0), n, sh_s, sh_t, sh_n, np.where(valid, t, 0.0), shape, rho)


def hide_emitters(value):
    """The value of <boolean name="hide_emitters"> (the text given); ValueError unless true or false."""
    if value.lower() not in ("true", "false"):
        raise ValueError(f"<boolean name='hide_emitters'> is {value!r}, not true or false")
    return value.lower() == "true"


def direct_settings(integrator):
    """The parameters of an <integrator> element (None: none) as Mitsuba's `direct` reads them
    (`shading_samples` sets both sample counts unless they are given); ValueError for a bad value."""
    values = {"emitter_samples": None, "bsdf_samples": None, "shading_samples": 1, "hide_emitters": False}
    for el in [] if integrator is None else integrator:
        name, value = el.get("name"), el.get("value", "").strip()
        if el.tag == "integer" and name in values and name != "hide_emitters":
            if not value.isdigit():
                raise ValueError(f"<integer name={name!r}> is {value!r}, not a count of at least 0")
            values[name] = int(value)
        elif el.tag == "boolean" and name == "hide_emitters":
            values[name] = hide_emitters(value)
    emitter, bsdf = (values["shading_samples"] if values[k] is None else values[k]
                     for k in ("emitter_samples", "bsdf_samples"))
    if emitter + bsdf == 0:
        raise ValueError("direct needs emitter_samples + bsdf_samples > 0")
    return DirectSettings(emitter, bsdf, values["hide_emitters"])


def power_heuristic(a, b):
    """Weight of the strategy of density a against b (Mitsuba's mis_weight: 0 where a is 0)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(a > 0, a * a / (a * a + b * b), 0.0)


class Tracer:
    """Rays leaving hit points, traced by Mitsuba. `offset(p, t)`: how far off its surface a ray starts."""

    def __init__(self, scene, mi, dr, offset):
        self.scene, self.mi, self.dr, self.offset = scene, mi, dr, offset

    def _ray(self, o, d, maxt=None):
        mi = self.mi
        f32 = lambda a: mi.Float(np.ascontiguousarray(a, dtype=np.float32))  # noqa: E731
        ray = mi.Ray3f(mi.Point3f(*map(f32, o)), mi.Vector3f(*map(f32, d)))
        if maxt is not None:
            ray.maxt = f32(maxt)
        return ray

    def origin(self, hits, d):
        """The hit points moved off their surfaces along the geometric normal, to the side d leaves by."""
        return hits.p + hits.n * np.copysign(self.offset(hits.p, hits.t), dot(hits.n, d))

    def visible(self, hits, d, dist, active):
        """Whether nothing blocks the segment of length dist (inf: the ray) from each hit point along d."""
        o = self.origin(hits, d)
        finite = np.isfinite(dist)
        target = hits.p + d * np.where(finite, dist, 0)
        # Toward a point: the unnormalised direction, ending just short of it (Mitsuba's ShadowEpsilon).
        direction = np.where(finite, target - o, d)
        maxt = np.where(finite, 1 - float(self.mi.math.ShadowEpsilon), np.inf)
        blocked = self.scene.ray_test(self._ray(o, direction, maxt), self.mi.Bool(active))
        return active & ~np.array(blocked, dtype=bool)

    def trace(self, hits, d, active):
        """What rays from the hit points along d find (where `active`)."""
        si = self.scene.ray_intersect(self._ray(self.origin(hits, d), d), self.mi.Bool(active))
        return Hits.of(si, self.mi, self.dr)


def emitted(lights, x, hits, d):
    """Per non-delta light, (pdf, radiance): the radiance arriving along d at the points x (the camera's, or
    surface points) from the light each ray of `hits` reached (an area light's front side, or the environment
    where it escaped), and the light's density by solid angle of having sampled that direction from x."""
    return [light.arriving(x, hits, d) for light in lights if not light.delta]


def cosine_hemisphere(hits, u):
    """Directions by the cosine-weighted hemisphere about the shading normal, and their cosines."""
    z = np.sqrt(1 - u[0])
    r, phi = np.sqrt(u[0]), 2 * math.pi * u[1]
    return hits.sh_s * (r * np.cos(phi)) + hits.sh_t * (r * np.sin(phi)) + hits.sh_n * z, z


def light_sample(lights, which, x, u):
    """Per lane, a sample of the light `which` names, from x: (d, dist, radiance, pdf, delta)."""
    samples = [light.sample(x, u) for light in lights]
    first = samples[0]
    d, dist, radiance, pdf = first.d, first.dist, first.radiance, first.pdf
    for i, s in enumerate(samples[1:], 1):
        lane = which == i
        d, dist, radiance, pdf = (np.where(lane, new, old) for new, old in
                                  ((s.d, d), (s.dist, dist), (s.radiance, radiance), (s.pdf, pdf)))
    return d, dist, radiance, pdf, np.array([light.delta for light in lights])[which]


def direct(tracer, lights, ray_o, ray_d, hits, rng, settings, bug=None):
    """The radiance of each camera ray (3, n): `ray_o`, `ray_d` their origins and directions, `hits` what they
    found. `bug` "direct-no-cosine" plants a BSDF evaluated without the cosine at the surface."""
    n = ray_d.shape[1]
    result = np.zeros((3, n))
    if not settings.hide_emitters:
        for _, radiance in emitted(lights, ray_o, hits, ray_d):
            result += radiance
    # One-sided: a surface seen from behind its shading normal reflects nothing.
    active = hits.valid & (dot(hits.sh_n, -ray_d) > 0)
    total = settings.emitter_samples + settings.bsdf_samples
    share_e, share_b = settings.emitter_samples / total, settings.bsdf_samples / total
    pick = 1 / len(lights)  # the chance of each light: uniform, Mitsuba's default

    for _ in range(settings.emitter_samples):
        which = np.minimum((rng.random(n) * len(lights)).astype(int), len(lights) - 1)
        d, dist, radiance, pdf, delta = light_sample(lights, which, hits.p, rng.random((2, n)))
        cos = dot(hits.sh_n, d)
        bsdf = hits.rho / math.pi * (np.where(cos > 0, 1.0, 0.0) if bug == "direct-no-cosine" else np.maximum(cos, 0))
        value = np.where(pdf > 0, radiance / np.where(pdf > 0, pdf * pick, 1), 0.0)
        weight = np.where(delta, 1.0, power_heuristic(pdf * pick * share_e, np.maximum(cos, 0) / math.pi * share_b))
        seen = tracer.visible(hits, d, dist, active & (cos > 0) & (pdf > 0))
        result += np.where(seen, bsdf * value * weight, 0.0) / settings.emitter_samples

    for _ in range(settings.bsdf_samples):
        d, cos = cosine_hemisphere(hits, rng.random((2, n)))
        bsdf_pdf = cos / math.pi
        found = tracer.trace(hits, d, active)
        for light_pdf, radiance in emitted(lights, hits.p, found, d):
            weight = power_heuristic(bsdf_pdf * share_b, light_pdf * pick * share_e)
            # The sample's value f / pdf is rho: the cosine and the 1/pi cancel.
            result += np.where(active, hits.rho * radiance * weight, 0.0) / settings.bsdf_samples
    return result
