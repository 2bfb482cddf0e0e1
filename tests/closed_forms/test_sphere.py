"""The sphere resting on a floor: its closed forms against numeric integration, and the analytic engine's
image against brute-force Monte Carlo written here, apart from harness/closed_forms/sphere.py."""
import importlib.util

import numpy as np
import pytest

from harness.engines.analytic import AnalyticEngine, load
from harness.closed_forms.plane_scene import NotAnalytic, load_plane_scene
from harness.closed_forms.sphere import ao_visible, segment_crosses_sphere
from harness.images.suite import SCENES_DIR

SCALES = ("milli", "unit", "kilo")


def _scene(scale: str = "unit", res: int = 32):
    return load(str(SCENES_DIR / f"sphere_floor_{scale}.xml"), {"res": str(res)})


def _cosine_dirs(rng, normals: np.ndarray) -> np.ndarray:
    """One cosine-weighted direction about each normal (n, 3)."""
    u1, u2 = rng.random(len(normals)), rng.random(len(normals))
    r, phi = np.sqrt(u1), 2 * np.pi * u2
    helper = np.where(np.abs(normals[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
    t = np.cross(normals, helper)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    b = np.cross(normals, t)
    return (r * np.cos(phi))[:, None] * t + (r * np.sin(phi))[:, None] * b + np.sqrt(1 - u1)[:, None] * normals


def _blocked(p: np.ndarray, d: np.ndarray, center: np.ndarray, radius: float, floor_half: float) -> np.ndarray:
    """Brute force: whether rays from p along d meet the sphere (closest approach) or the finite floor z = 0."""
    along = np.sum((center - p) * d, axis=1)
    closest = np.linalg.norm(p + np.clip(along, 0, None)[:, None] * d - center, axis=1)
    sphere = (along > 0) & (closest < radius)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -p[:, 2] / d[:, 2]
    q = p + np.where(t > 0, t, 0)[:, None] * d
    floor = (t > 1e-9 * radius) & np.all(np.abs(q[:, :2]) <= floor_half, axis=1)
    return sphere | floor


@pytest.mark.parametrize("distance", [1.0, 1.3, 2.5])
def test_floor_occlusion_is_one_minus_r_over_d_cubed(distance):
    rng = np.random.default_rng(7)
    n = 400_000
    s = _scene()
    p = np.tile([distance, 0.0, 0.0], (n, 1))  # on the floor, `distance` from the contact point
    up = np.tile([0.0, 0.0, 1.0], (n, 1))
    seen = 1 - _blocked(p, _cosine_dirs(rng, up), s.sphere.center, 1.0, 2e4).mean()
    exact = float(ao_visible(s, p[:1], up[:1])[0, 0])
    assert exact == pytest.approx(1 - (1 / np.hypot(distance, 1.0)) ** 3, rel=1e-12)
    assert abs(seen - exact) < 4 * np.sqrt(exact * (1 - exact) / n)


@pytest.mark.parametrize("polar", [0.3, 1.2, 2.0, 2.8])
def test_sphere_occlusion_is_half_of_one_plus_n_z(polar):
    """The floor (finite, 2e4 radii) cuts the cosine lobe; the sphere cannot occlude itself."""
    import dataclasses

    rng = np.random.default_rng(11)
    n = 400_000
    s = dataclasses.replace(_scene(), surface="sphere")
    normal = np.array([np.sin(polar), 0.0, np.cos(polar)])
    p = np.tile(s.sphere.center + normal, (n, 1))
    seen = 1 - _blocked(p + 1e-9 * normal, _cosine_dirs(rng, np.tile(normal, (n, 1))), s.sphere.center, 1.0,
                        2e4).mean()
    exact = float(ao_visible(s, p[:1], normal)[0, 0])
    assert exact == pytest.approx((1 + np.cos(polar)) / 2, rel=1e-12)
    assert abs(seen - exact) < 4 * np.sqrt(exact * (1 - exact) / n) + 1.3e-4


@pytest.mark.slow
def test_shadow_test_against_marching_along_the_segment():
    rng = np.random.default_rng(3)
    s = _scene()
    light = s.lights[0][0]
    p = np.concatenate([rng.uniform(-4, 4, (4000, 2)), np.zeros((4000, 1))], axis=1)
    steps = np.linspace(0, 1, 4001)[1:-1]
    inside = np.linalg.norm(p[:, None] + steps[None, :, None] * (light - p)[:, None] - s.sphere.center, axis=2) < 1
    marched = inside.any(axis=1)
    exact = segment_crosses_sphere(s, p, light)
    # Marching can miss a chord shorter than its step; those are the only disagreements allowed.
    assert np.all(marched <= exact) and (exact & ~marched).sum() <= 4
    assert 200 < exact.sum() < 3800  # the test sees both lit and shadowed floor


def test_the_scenes_are_one_image_at_every_scale():
    images = [AnalyticEngine().render(str(SCENES_DIR / f"sphere_floor_{sc}.xml"), "simple", 2, 2, 5,
                                      {"res": "16"}).batches for sc in SCALES]
    assert np.allclose(images[0], images[1], rtol=1e-4, atol=1e-7)
    assert np.allclose(images[2], images[1], rtol=1e-4, atol=1e-7)


def test_what_the_engine_supports_is_explicit(tmp_path):
    path = str(SCENES_DIR / "sphere_floor_unit.xml")
    assert all(AnalyticEngine.supports(path, None, i) for i in ("normals", "simple", "ao"))
    assert not AnalyticEngine.supports(str(SCENES_DIR / "sphere_plane.xml"))  # a mesh sphere
    floating = tmp_path / "floating.xml"
    floating.write_text(open(path).read().replace('name="center" value="0, 0, 1"', 'name="center" value="0, 0, 1.5"'))
    with pytest.raises(NotAnalytic, match="not its radius"):
        load(str(floating))
    small = tmp_path / "small_floor.xml"
    small.write_text(_floor_scene(floor=50.0))
    assert load_plane_scene(str(small)).sphere is not None  # it parses, but its closed forms do not hold
    assert not AnalyticEngine.supports(str(small))


def _floor_scene(floor: float = 2e4, tiles=None) -> str:
    """sphere_floor_unit's text from its generator, with another floor half-size or other tiles."""
    spec = importlib.util.spec_from_file_location("make_sphere_floor", SCENES_DIR / "make_sphere_floor.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    gen.FLOOR = floor
    if tiles is not None:
        gen.floor_tiles = lambda r: tiles
    return gen.scene_text("unit", 1.0)


def test_a_tiled_floor_is_one_plane_and_a_bad_tiling_is_refused(tmp_path):
    """The floor is five rectangles (a small one under the camera, strips around it): the closed forms see
    the one 2e4-radius square they tile; tiles with a gap or an overlap are not a plane."""
    plane = load_plane_scene(str(SCENES_DIR / "sphere_floor_unit.xml")).plane
    assert np.allclose(plane, np.diag([2e4, 2e4, 1.0, 1.0]))
    for name, tiles in (("gap", [(0, 0, 32, 32), (-1e4, 0, 9e3, 2e4)]), ("overlap", [(0, 0, 2e4, 2e4), (0, 0, 32, 32)])):
        bad = tmp_path / f"{name}.xml"
        bad.write_text(_floor_scene(tiles=tiles))
        with pytest.raises(NotAnalytic, match="overlap or leave a gap"):
            load_plane_scene(str(bad))


def _pixel_ray(s, x: float, y: float):
    """The camera ray through film position (x, y) in pixels, from the perspective camera's definition."""
    local = np.stack([(1 - 2 * x / s.width) * s.tan_half_x, (1 - 2 * y / s.height) * s.tan_half_x * s.height
                      / s.width, np.ones_like(x)], axis=-1)
    local /= np.linalg.norm(local, axis=-1, keepdims=True)
    return local @ s.to_world.T


def _brute_force_pixel(s, integrator: str, row: int, col: int, n: int, rng) -> tuple[float, float]:
    """Mean and standard error of the blue channel over the pixel: first hit by closest approach to the sphere
    and the plane z = 0, then one occlusion ray (ao) or the point light and a shadow ray (simple)."""
    d = _pixel_ray(s, col + rng.random(n), row + rng.random(n))
    c, r = s.sphere.center, s.sphere.radius
    o = np.broadcast_to(s.origin, d.shape)
    along = d @ (c - s.origin)
    miss2 = np.sum((s.origin - c) ** 2) - along**2
    t_sphere = np.where(miss2 < r * r, along - np.sqrt(np.clip(r * r - miss2, 0, None)), np.inf)
    t_floor = np.where(d[:, 2] < 0, -s.origin[2] / d[:, 2], np.inf)
    on_sphere = t_sphere < t_floor
    p = o + np.minimum(t_sphere, t_floor)[:, None] * d
    normal = np.where(on_sphere[:, None], (p - c) / r, [0.0, 0.0, 1.0])
    rho = np.where(on_sphere, s.sphere.reflectance[2], s.reflectance[2])
    spawn = p + 1e-9 * r * normal
    if integrator == "ao":  # it reads no material
        value = (~_blocked(spawn, _cosine_dirs(rng, normal), c, r, 2e4 * r)).astype(np.float64)
    else:
        light, intensity = s.lights[0]
        to_light = light - p
        dist = np.linalg.norm(to_light, axis=1)
        cos = np.clip(np.sum(to_light * normal, axis=1) / dist, 0, None)
        along = np.sum((c - spawn) * to_light, axis=1) / dist
        closest = np.linalg.norm(spawn + np.clip(along, 0, dist)[:, None] * to_light / dist[:, None] - c, axis=1)
        value = rho / np.pi * intensity[2] * cos / dist**2 * (closest >= r)
    return float(value.mean()), float(value.std() / np.sqrt(n))


@pytest.mark.slow
@pytest.mark.parametrize("integrator", ["ao", "simple"])
@pytest.mark.parametrize("scale", ["unit", "kilo"])
def test_engine_against_brute_force_monte_carlo(integrator, scale):
    s = _scene(scale)
    image = AnalyticEngine().render(str(SCENES_DIR / f"sphere_floor_{scale}.xml"), integrator, 256, 4, 1,
                                    {"res": "32"}).batches.astype(np.float64)
    rng = np.random.default_rng(5)
    # On the sphere lit and unlit, on the floor beside it, on the shadow's two edges, far away, in the shadow.
    for row, col in [(4, 12), (12, 16), (16, 26), (21, 9), (19, 23), (0, 0), (26, 20)]:
        mean, se = _brute_force_pixel(s, integrator, row, col, 60_000, rng)
        mcval = image[:, row, col, 2]
        se_engine = mcval.std(ddof=1) / np.sqrt(len(mcval))
        # All of the engine's batches can miss a far floor pixel's rare occlusion (ao): its SE is then at least
        # what the brute force's per-sample spread predicts for the engine's 4 x 256 samples.
        se_engine = max(se_engine, se * np.sqrt(60_000 / (4 * 256)))
        assert abs(mcval.mean() - mean) < 5 * np.hypot(se, se_engine) + 1e-6, (row, col)
