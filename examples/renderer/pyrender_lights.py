"""pyrender's emitters for `direct`: point lights, the constant environment and area lights on rectangles,
disks and spheres, each with sample / eval / pdf by solid angle, in numpy (float64, arrays of shape (3, n)).

Mitsuba 3 only reads the scene: each emitter's values come through `mi.traverse` and each area light's shape
through its `to_world`. How a light is sampled is pyrender's own: a rectangle or disk uniformly by area,
turned into a density by solid angle, pdf = dist^2 / (|cos_l| * area); a sphere by the cone of directions it
subtends, as Mitsuba does, or (--sphere-sampling area) uniformly over its whole surface: another unbiased
estimator of the same image, noisier, which its engine file then declares (other_estimators).
"""
import math

import numpy as np

#: Area lights pyrender models, by Mitsuba's class name of the shape.
AREA_SHAPES = ("Rectangle", "Disk", "Sphere")


class LightError(ValueError):
    """A scene with an emitter pyrender does not model (one line saying which and why)."""


def rgb(value):
    a = np.array(value, dtype=np.float64).ravel()
    return np.repeat(a, 3) if a.size == 1 else a[:3]


def dot(a, b):
    return np.sum(a * b, axis=0)


def uniform_sphere(u):
    """Directions uniform on the unit sphere from u in [0, 1)^2 (shape (2, n))."""
    z = 1 - 2 * u[0]
    r = np.sqrt(np.maximum(0, 1 - z * z))
    phi = 2 * math.pi * u[1]
    return np.stack([r * np.cos(phi), r * np.sin(phi), z])


class LightSample:
    """Toward a sampled point of a light: unit direction `d`, distance `dist` (inf: no point), `radiance`
    arriving (0 where the light faces away), density `pdf` by solid angle (1 for a delta light), `delta`."""

    def __init__(self, d, dist, radiance, pdf, delta):
        self.d, self.dist, self.radiance, self.pdf, self.delta = d, dist, radiance, pdf, delta


class PointLight:
    delta = True

    def __init__(self, position, intensity):
        self.position, self.intensity = position[:, None], intensity[:, None]

    def sample(self, x, u):
        to_light = self.position - x
        dist = np.sqrt(dot(to_light, to_light))
        return LightSample(to_light / dist, dist, self.intensity / dist**2, np.ones_like(dist), True)


class Environment:
    """The `constant` emitter: radiance L from every direction, sampled uniformly on the sphere."""
    delta = False

    def __init__(self, radiance):
        self.radiance = radiance[:, None]

    def sample(self, x, u):
        n = x.shape[1]
        return LightSample(uniform_sphere(u), np.full(n, np.inf), np.repeat(self.radiance, n, axis=1),
                           np.full(n, 1 / (4 * math.pi)), False)

    def arriving(self, x, hits, d):
        """(pdf, radiance) along d where the rays of `hits` escaped the scene."""
        gone = ~hits.valid
        return np.where(gone, 1 / (4 * math.pi), 0.0), np.where(gone, self.radiance, 0.0)


class AreaLight:
    """Constant radiance on the front side of a rectangle or disk, sampled uniformly by area.
    `area_measure`: the planted bug that leaves the pdf in area measure (1 / area, no dist^2 / cos)."""
    delta = False

    def __init__(self, to_world, radiance, shape_id, kind="Rectangle", area_measure=False, flipped=False):
        self.radiance, self.shape_id, self.kind, self.area_measure = radiance[:, None], shape_id, kind, area_measure
        m = np.asarray(to_world, dtype=np.float64)
        self.linear, self.origin = m[:3, :3], m[:3, 3:4]
        # The unit square [-1, 1]^2 or the unit disk in z = 0, mapped by to_world (normals by its inverse transpose);
        # flip_normals turns its front (the side that emits) around.
        normal = np.linalg.inv(self.linear).T @ np.array([0.0, 0.0, -1.0 if flipped else 1.0])
        self.normal = (normal / np.linalg.norm(normal))[:, None]
        side = np.linalg.norm(np.cross(self.linear[:, 0], self.linear[:, 1]))
        self.area = side * (4 if kind == "Rectangle" else math.pi)

    def _point(self, u):
        """A point uniform by area on the shape, and its normal there."""
        if self.kind == "Rectangle":
            local = np.stack([2 * u[0] - 1, 2 * u[1] - 1])
        else:
            r, phi = np.sqrt(u[0]), 2 * math.pi * u[1]
            local = np.stack([r * np.cos(phi), r * np.sin(phi)])
        return self.origin + self.linear[:, :2] @ local, np.repeat(self.normal, u.shape[1], axis=1)

    def pdf(self, x, dist, cos_light):
        """The density by solid angle, seen from x, of the point at `dist` whose normal makes cos_light with the
        ray (uniform by area: dist^2 / (|cos_light| area))."""
        if self.area_measure:
            return np.full_like(dist, 1 / self.area)
        with np.errstate(divide="ignore", invalid="ignore"):  # 0 where cos_light is 0
            return np.where(cos_light != 0, dist**2 / (np.abs(cos_light) * self.area), 0.0)

    def arriving(self, x, hits, d):
        """(pdf, radiance) along d from x where the rays of `hits` reached this light's front side."""
        on = hits.valid & (hits.shape == self.shape_id) & (dot(hits.sh_n, -d) > 0)
        return np.where(on, self.pdf(x, hits.t, dot(hits.n, d)), 0.0), np.where(on, self.radiance, 0.0)

    def sample(self, x, u):
        y, n = self._point(u)
        to_light = y - x
        dist = np.sqrt(dot(to_light, to_light))
        d = to_light / dist
        cos_light = -dot(n, d)                      # > 0: x is in front of the light
        faces = cos_light > 0
        return LightSample(d, dist, np.where(faces, self.radiance, 0.0), self.pdf(x, dist, cos_light), False)


class SphereLight(AreaLight):
    """Constant radiance on a sphere: from a point outside it, directions uniform in the cone it subtends
    (as Mitsuba samples it; by area, half the samples land on its far side); from inside, or on it, uniform by
    area. The sphere's own hits lie on either side of it by float32 rounding: within INSIDE_MARGIN of the
    radius a point counts as on it (the cone's near side would be the point itself), in sample() and pdf()
    alike, so that the two agree."""

    #: Relative distance from the surface within which a point counts as on the sphere.
    INSIDE_MARGIN = 1e-3

    def __init__(self, to_world, radiance, shape_id, area_measure=False, by_area=False, flipped=False):
        m = np.asarray(to_world, dtype=np.float64)
        self.radiance, self.shape_id, self.area_measure = radiance[:, None], shape_id, area_measure
        self.side = -1.0 if flipped else 1.0  # flip_normals: it emits inwards
        self.by_area = by_area  # uniform over the whole surface: the far half's samples are wasted
        self.center, self.radius = m[:3, 3:4], float(np.linalg.norm(m[:3, 0]))
        self.area = 4 * math.pi * self.radius**2

    def _point(self, u):
        n = uniform_sphere(u)
        return self.center + self.radius * n, self.side * n

    def _cone(self, x):
        """Unit axis toward the centre, distance to it, the cosine of the cone's half-angle (0 inside) and the
        density of directions uniform in the cone, 1 / (2 pi (1 - cos)), written to keep its digits far away."""
        to_c = self.center - x
        dc = np.sqrt(dot(to_c, to_c))
        sin2 = (self.radius / dc) ** 2
        cos_a = np.sqrt(np.maximum(0, 1 - sin2))
        return to_c / dc, dc, cos_a, (1 + cos_a) / (2 * math.pi * sin2)

    def pdf(self, x, dist, cos_light):
        if self.by_area:
            return super().pdf(x, dist, cos_light)
        _, dc, _, cone_pdf = self._cone(x)
        return np.where(self._outside(dc), cone_pdf, super().pdf(x, dist, cos_light))

    def _outside(self, dc):
        return dc > self.radius * (1 + self.INSIDE_MARGIN)

    def sample(self, x, u):
        by_area = super().sample(x, u)
        if self.by_area:
            return by_area
        w, dc, cos_a, cone_pdf = self._cone(x)
        cos_t = 1 - u[0] * (1 - cos_a)
        sin_t, phi = np.sqrt(np.maximum(0, 1 - cos_t**2)), 2 * math.pi * u[1]
        # An orthonormal frame about w (Duff et al. 2017).
        sign = np.copysign(1.0, w[2])
        a = -1 / (sign + w[2])
        b = w[0] * w[1] * a
        s = np.stack([1 + sign * w[0] ** 2 * a, sign * b, -sign * w[0]])
        t = np.stack([b, sign + w[1] ** 2 * a, -w[1]])
        d = s * (sin_t * np.cos(phi)) + t * (sin_t * np.sin(phi)) + w * cos_t
        dist = dc * cos_t - np.sqrt(np.maximum(0, self.radius**2 - (dc * sin_t) ** 2))  # the near side
        outside = self._outside(dc)
        pick = lambda a, b: np.where(outside, a, b)  # noqa: E731
        return LightSample(pick(d, by_area.d), pick(dist, by_area.dist), pick(self.radiance, by_area.radiance),
                           pick(cone_pdf, by_area.pdf), False)


def _flipped(shape, to_world, mi):
    """Whether the shape's flip_normals is set (Mitsuba does not list it among its parameters): the normal of a
    point it samples against the one its to_world gives there (outward for a sphere, +z mapped for the others)."""
    ps = shape.sample_position(0.0, mi.Point2f(0.3, 0.6))
    n, p = (np.array(v, dtype=np.float64).ravel() for v in (ps.n, ps.p))
    m = np.asarray(to_world, dtype=np.float64)
    if shape.class_name() == "Sphere":
        unflipped = p - m[:3, 3]
    else:
        unflipped = np.linalg.inv(m[:3, :3]).T @ np.array([0.0, 0.0, 1.0])
    return float(n @ unflipped) < 0


def scene_lights(scene, mi, dr, area_measure=False, sphere_by_area=False):
    """The scene's emitters as pyrender's lights; LightError for one it does not model. `sphere_by_area`: sphere
    lights sampled uniformly by area rather than by their cone."""
    lights = []
    for e in scene.emitters():
        params, kind = mi.traverse(e), e.class_name()
        if kind == "PointLight":
            lights.append(PointLight(rgb(params["position"]), rgb(params["intensity.value"])))
        elif kind == "ConstantBackgroundEmitter":
            lights.append(Environment(rgb(params["radiance.value"])))
        elif kind == "AreaLight":
            shape = e.get_shape()
            if shape.class_name() not in AREA_SHAPES:
                raise LightError(f"an area light on a {shape.class_name()} (pyrender's direct samples area lights "
                                 f"on {', '.join(AREA_SHAPES)} only)")
            if "radiance.value" not in params:
                raise LightError("an area light whose radiance is a texture (pyrender's is constant)")
            shape_id = int(np.array(dr.reinterpret_array(mi.UInt32, mi.ShapePtr(shape)))[0])
            matrix = np.array(mi.traverse(shape)["to_world"].matrix)[..., 0]
            radiance = rgb(params["radiance.value"])
            flipped = _flipped(shape, matrix, mi)
            lights.append(SphereLight(matrix, radiance, shape_id, area_measure, sphere_by_area, flipped)
                          if shape.class_name() == "Sphere"
                          else AreaLight(matrix, radiance, shape_id, shape.class_name(), area_measure, flipped))
        else:
            raise LightError(f"a {kind} emitter (pyrender's direct reads point, constant and area lights)")
    return lights
