"""The area lights' closed forms against quadrature over the light's surface (tests/helpers/light_quadrature.py),
at points under the light, under its edges and corners, and far to the side; each with a planted wrong twin
(the polygon formula with the other sign convention, a sphere missing its cosine, a disk taken as seen on its
axis) that the same check rejects."""
import numpy as np
import pytest

from harness.closed_forms.area_lights import (DiskLight, PolygonLight, SphereLight, disk_omega, disk_omega_on_axis,
                                              polygon_omega, sphere_omega)
from tests.helpers import light_quadrature as quad

UP = np.array([0.0, 1.0, 0.0])
ONE = np.ones(3)
#: The agreement asked of a closed form, relative to the largest value over the points, and the disagreement
#: that shows a twin wrong.
TOLERANCE, WRONG = 1e-9, 1e-3


def _rotation(axis, degrees) -> np.ndarray:
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = np.radians(degrees)
    return np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k


#: A 1 x 0.6 rectangle 2 above the floor, tilted by 20 degrees and turned by 30: its corner, two edges.
TURN = _rotation(UP, 30) @ _rotation([0, 0, 1], 20)
CORNER = np.array([0, 2.0, 0]) + TURN @ np.array([-0.5, 0, -0.3])
E1, E2 = TURN @ np.array([1.0, 0, 0]), TURN @ np.array([0, 0, 0.6])  # e1 x e2 points down: the emitting side
RECT = PolygonLight(np.array([CORNER, CORNER + E1, CORNER + E1 + E2, CORNER + E2]), TURN @ -UP, ONE)


def _floor_points(center: np.ndarray, half: float) -> np.ndarray:
    """Floor points under the light's centre, edges and corners (and just inside and outside them), and far."""
    c = np.array([center[0], 0.0, center[2]])
    near = [c + np.array([x, 0, z]) for x in (-1.02 * half, -half, -0.98 * half, 0, 0.5 * half, half)
            for z in (-half, 0, 0.98 * half, 1.02 * half)]
    far = [c + np.array(v, float) for v in ((4, 0, 0), (0, 0, -6), (-3, 0, 5), (8, 0, 8), (20, 0, 1))]
    return np.array(near + far)


def _agreement(closed, oracle, points, normals) -> float:
    """The largest difference between the closed form and the oracle, over the largest oracle value."""
    exact = np.array([oracle(p, n) for p, n in zip(points, normals)])
    values = np.array([float(closed(p, n)) for p, n in zip(points, normals)])
    return float(np.max(np.abs(values - exact)) / np.max(np.abs(exact)))


def _rect_oracle(p, n):
    return quad.rectangle(CORNER, E1, E2, p, n)


def _floor(points):
    return points, np.broadcast_to(UP, points.shape)


def test_the_oracle_has_converged():
    """Twice the panels move the quadrature by far less than the tolerance: it can decide."""
    p = np.array([0.4, 0.0, 0.3])
    assert abs(quad.rectangle(CORNER, E1, E2, p, UP) - quad.rectangle(CORNER, E1, E2, p, UP, panels=16)) < 1e-12
    disk = DiskLight(np.array([0, 2.0, 0]), -UP, 0.5, ONE)
    assert abs(quad.disk(disk.center, disk.normal, 0.5, p, UP)
               - quad.disk(disk.center, disk.normal, 0.5, p, UP, panels=16, azimuths=1024)) < 1e-12
    assert abs(quad.sphere(np.array([0, 2.0, 0]), 0.5, p, UP)
               - quad.sphere(np.array([0, 2.0, 0]), 0.5, p, UP, panels=16, azimuths=1024)) < 1e-12


def test_lamberts_formula_on_a_floor():
    points, normals = _floor(_floor_points(np.array([0, 2.0, 0]), 0.55))
    assert _agreement(lambda p, n: polygon_omega(RECT, p, n), _rect_oracle, points, normals) < TOLERANCE


def test_lamberts_formula_at_any_orientation_under_the_light():
    """Tilted receivers (a wall, a slope) wherever the rectangle is wholly above their horizon."""
    rng = np.random.default_rng(7)
    points = np.column_stack([rng.uniform(-2, 2, 40), rng.uniform(0, 1.5, 40), rng.uniform(-2, 2, 40)])
    normals = rng.normal(size=(40, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    above = [np.all((RECT.vertices - p) @ n > 0) for p, n in zip(points, normals)]
    points, normals = points[above], normals[above]
    assert len(points) >= 10
    assert _agreement(lambda p, n: polygon_omega(RECT, p, n), _rect_oracle, points, normals) < TOLERANCE


def test_lamberts_formula_is_zero_behind_the_light():
    """The rectangle emits on its front side only: beyond where its plane meets the floor it gives nothing."""
    behind = np.array([[-8.0, 0, 2.0], [-10.0, 0, -1.0]])
    assert np.all((behind - CORNER) @ RECT.normal < 0)
    assert np.all(polygon_omega(RECT, behind, UP) == 0)
    assert all(_rect_oracle(p, UP) == 0 for p in behind)


def test_lamberts_formula_with_the_other_sign_convention_is_rejected():
    """Planted twin: the edges' normals taken the other way round (gamma = a x b): the front side reads 0."""
    wrong = PolygonLight(RECT.vertices[::-1], RECT.normal, ONE)  # clockwise about the emitting normal
    points, normals = _floor(_floor_points(np.array([0, 2.0, 0]), 0.55))
    assert _agreement(lambda p, n: polygon_omega(wrong, p, n), _rect_oracle, points, normals) > WRONG


DISK = DiskLight(np.array([0.3, 2.0, -0.5]), -UP, 0.5, ONE)


def _disk_oracle(p, n):
    return quad.disk(DISK.center, DISK.normal, DISK.radius, p, n)


def test_the_disk_off_its_axis():
    points, normals = _floor(_floor_points(DISK.center, DISK.radius))
    assert _agreement(lambda p, n: disk_omega(DISK, p, n), _disk_oracle, points, normals) < TOLERANCE


def test_the_disk_on_its_axis_is_pi_sin2_alpha():
    heights = np.array([0.05, 0.5, 2.0, 40.0])
    points = DISK.center - heights[:, None] * UP
    assert np.allclose(disk_omega(DISK, points, UP), disk_omega_on_axis(DISK, heights), rtol=1e-13)


def test_a_disk_taken_as_seen_on_its_axis_is_rejected():
    """Planted twin: pi sin^2(alpha) with the distance to the centre for the height, off the axis too."""
    def on_axis(p, n):
        return disk_omega_on_axis(DISK, np.linalg.norm(DISK.center - p))

    points, normals = _floor(_floor_points(DISK.center, DISK.radius))
    assert _agreement(on_axis, _disk_oracle, points, normals) > WRONG


SPHERE = SphereLight(np.array([0.0, 2.0, -0.5]), 0.5, ONE)


def _sphere_oracle(p, n):
    return quad.sphere(SPHERE.center, SPHERE.radius, p, n)


@pytest.mark.parametrize("height", [2.0, 0.51])
def test_the_sphere_wholly_above_the_horizon(height):
    """Also a sphere just clear of the floor (its lowest point 0.01 above it)."""
    light = SphereLight(np.array([0.0, height, -0.5]), 0.5, ONE)
    points, normals = _floor(_floor_points(light.center, light.radius))

    def oracle(p, n):
        return quad.sphere(light.center, light.radius, p, n, panels=32 if height < 1 else 8)

    assert _agreement(lambda p, n: sphere_omega(light, p, n), oracle, points, normals) < TOLERANCE


def test_a_sphere_missing_its_cosine_is_rejected():
    """Planted twin: pi (R/d)^2 without cos(theta)."""
    def no_cosine(p, n):
        return np.pi * (SPHERE.radius / np.linalg.norm(SPHERE.center - p)) ** 2

    points, normals = _floor(_floor_points(SPHERE.center, SPHERE.radius))
    assert _agreement(no_cosine, _sphere_oracle, points, normals) > WRONG


def test_a_closed_form_missing_the_lights_cosine_is_rejected_by_the_oracle():
    """Planted twin of the oracle's own kernel: cos(theta_p) / r^2 alone over the rectangle differs from
    Lambert's formula, so the oracle's agreement above is not an accident of its kernel."""
    def no_light_cosine(p, n):
        t, w = quad._gauss(8, 24)
        u, v = np.meshgrid(t, t, indexing="ij")
        x = CORNER + u[..., None] * E1 + v[..., None] * E2
        d = x - p
        r = np.linalg.norm(d, axis=-1)
        return float(np.einsum("i,j,ij->", w, w, (d @ n / r) / r**2) * np.linalg.norm(np.cross(E1, E2)))

    points, normals = _floor(_floor_points(np.array([0, 2.0, 0]), 0.55))
    assert _agreement(lambda p, n: polygon_omega(RECT, p, n), no_light_cosine, points, normals) > WRONG
