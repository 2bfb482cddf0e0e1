#!/usr/bin/env python3
"""pyrender: a small Monte Carlo renderer for mcval's engine contract (docs/engines.md).

Mitsuba 3 (variant llvm_ad_rgb) loads the scene and traces rays; the five
integrators (normals, simple, ao, direct in pyrender_direct.py with its lights
in pyrender_lights.py, and path in pyrender_path.py), the pixel sampling, the
random numbers and the image accumulation are pyrender's own, vectorised over
pixels x samples.

    pyrender.py SCENE --integrator NAME --spp N --seed S --width W --height H
                -o OUT.exr [--batches K] [--threads T] [--bug NAME] [--sphere-sampling cone|area]
    pyrender.py --version
"""
import argparse
import math
import os
import sys
import time
import xml.etree.ElementTree as ET

from pyrender_direct import Hits, Tracer, direct, direct_settings
from pyrender_lights import LightError, scene_lights
from pyrender_path import path, path_settings

VERSION = "pyrender 0.1"
INTEGRATORS = ("normals", "simple", "ao", "direct", "path")
BUGS = ("bright", "ao-uniform", "ao-albedo", "simple-no-cosine", "offset", "direct-no-cosine", "area-pdf", "path-rr")
MAX_RAYS = 1 << 21          # camera rays traced at once (memory bound)
MAX_RAYS_DIRECT = 1 << 18   # direct and path keep a dozen float64 arrays per camera ray
SPAWN_EPS = 1e-6            # relative offset of secondary rays (see spawn_origin)
BUG_OFFSET = 1e-2           # the 'offset' bug's absolute spawn offset


def fail(msg):
    print(f"pyrender: error: {msg}", file=sys.stderr)
    sys.exit(1)


class Parser(argparse.ArgumentParser):
    def error(self, message):          # argparse exits 2; the contract wants 1
        self.print_usage(sys.stderr)
        fail(message)


def parse_args(argv):
    p = Parser(prog="pyrender.py", description=__doc__.splitlines()[0])
    p.add_argument("scene")
    p.add_argument("--integrator", choices=INTEGRATORS, required=True)
    for opt in ("--spp", "--seed", "--width", "--height"):
        p.add_argument(opt, type=int, required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--batches", type=int, default=1,
                   help="independent images to render, each with --spp samples, written as the layers batch0 ... "
                        "(one process for them all: the start-up, Mitsuba's and the scene's, is paid once)")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--bug", choices=BUGS)
    p.add_argument("--sphere-sampling", choices=("cone", "area"), default="cone",
                   help="how direct samples a sphere light: by the cone it subtends (Mitsuba's estimator) or "
                        "uniformly by area (another unbiased estimator, noisier)")
    a = p.parse_args(argv)
    if min(a.spp, a.width, a.height, a.batches) < 1 or a.seed < 0:
        p.error("--spp, --width, --height and --batches must be positive, --seed non-negative")
    return a


def scene_xml(path, width, height, integrator):
    """The scene XML with the <integrator> and <sampler> removed (pyrender has
    its own) and the film size set to width x height, the stddev of the film's
    gaussian reconstruction filter (None for a box filter), and, for direct,
    its parameters or path's from the <integrator> (None for the others)."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        fail(f"cannot read scene {path!r}: {e}")
    if root.tag != "scene":
        fail(f"{path}: the root element is <{root.tag}>, not <scene>")
    try:
        readers = {"direct": direct_settings, "path": path_settings}
        settings = readers[integrator](root.find("integrator")) if integrator in readers else None
    except ValueError as e:
        fail(f"{path}: {e}")
    for el in root.findall("integrator"):
        root.remove(el)
    sensors = root.findall("sensor")
    if len(sensors) != 1:
        fail(f"{path}: expected one <sensor>, found {len(sensors)}")
    sensor = sensors[0]
    for el in sensor.findall("sampler"):
        sensor.remove(el)
    film = sensor.find("film")
    if film is None:
        film = ET.SubElement(sensor, "film", type="hdrfilm")
    for el in film.findall("integer"):
        if el.get("name") in ("width", "height"):
            film.remove(el)
    ET.SubElement(film, "integer", name="width", value=str(width))
    ET.SubElement(film, "integer", name="height", value=str(height))
    rfilter, stddev = film.find("rfilter"), None
    kind = "box" if rfilter is None else rfilter.get("type")
    if kind == "gaussian":
        el = rfilter.find("float[@name='stddev']")
        stddev = 0.5 if el is None else float(el.get("value"))
    elif kind != "box":
        fail(f"{path}: unsupported reconstruction filter {kind!r} (box, gaussian)")
    return ET.tostring(root, encoding="unicode"), stddev, settings


def rgb(value):
    a = np.array(value, dtype=np.float64).ravel()
    return np.repeat(a, 3) if a.size == 1 else a[:3]


def emitters(scene):
    """Point lights [(position, intensity)] and the constant emitter's radiance."""
    lights, env = [], None
    for e in scene.emitters():
        params = mi.traverse(e)
        if e.class_name() == "PointLight":
            lights.append((rgb(params["position"]), rgb(params["intensity.value"])))
        elif e.class_name() == "ConstantBackgroundEmitter":
            env = rgb(params["radiance.value"])
    return lights, (np.ones(3) if env is None else env)


def color(c):
    return mi.Color3f(*(float(x) for x in c))


def spawn_origin(si, d, bug):
    """Where a ray leaving the hit point towards d starts: off the surface, on
    d's side, by SPAWN_EPS * (max|p| + camera ray length), about 16 float32
    ulps of the hit point's rounding. It scales with the scene, so scaled and
    moved scenes render the same image."""
    if bug == "offset":
        mag = mi.Float(BUG_OFFSET)
    else:
        mag = SPAWN_EPS * (dr.max(dr.abs(si.p)) + si.t)
    return si.p + si.n * dr.mulsign(mag, dr.dot(si.n, d))


def spawn_to(si, target, bug):
    """A shadow ray from the hit point to target (maxt just short of it)."""
    o = spawn_origin(si, target - si.p, bug)
    ray = mi.Ray3f(o, target - o)    # (beware: Ray3f(o, d, x) takes x as the time)
    ray.maxt = mi.Float(1.0 - mi.math.ShadowEpsilon)
    return ray


def spawn(si, d, bug):
    """A ray leaving the hit point in direction d."""
    return mi.Ray3f(spawn_origin(si, d, bug), d)


def shade(scene, lights, env, integrator, ray, si, rng, n_rays, bug):
    """The value of each camera ray (Color3f)."""
    valid = si.is_valid()
    n = si.sh_frame.n
    if integrator == "normals":
        return dr.select(valid, mi.Color3f(n.x, n.y, n.z), mi.Color3f(0.0))
    # One-sided: seen from behind (w.r.t. the shading normal), a surface is black.
    active = valid & (dr.dot(n, -ray.d) > 0)
    rho = si.bsdf().eval_diffuse_reflectance(si, active)
    result = mi.Color3f(0.0)
    if integrator == "simple":
        for pos, intensity in lights:
            lp = mi.Point3f(*(float(x) for x in pos))
            to_light = lp - si.p
            r2 = dr.squared_norm(to_light)
            cos = dr.dot(n, to_light) * dr.rsqrt(r2)
            weight = mi.Float(1.0) if bug == "simple-no-cosine" else dr.maximum(cos, 0.0)
            lit = active & (weight > 0)
            lit &= ~scene.ray_test(spawn_to(si, lp, bug), lit)
            contrib = rho * color(intensity) * (weight / (math.pi * r2))
            result += dr.select(lit, contrib, 0.0)
    else:  # ao
        u = rng.random((2, n_rays), dtype=np.float32)
        u1, phi = mi.Float(u[0]), mi.Float(u[1]) * (2 * math.pi)
        if bug == "ao-uniform":  # uniform directions weighted 1 (instead of 2 cos)
            z = u1
        else:                    # cosine-weighted: (1/pi) V cos / pdf = V
            z = dr.safe_sqrt(1.0 - u1)
        r = dr.safe_sqrt(1.0 - z * z)
        d = si.sh_frame.to_world(mi.Vector3f(r * dr.cos(phi), r * dr.sin(phi), z))
        seen = active & ~scene.ray_test(spawn(si, d, bug), active)
        # ao reads no material: a visible direction counts L, whatever the surface's reflectance.
        lit = rho * color(env) if bug == "ao-albedo" else color(env)
        result = dr.select(seen, lit, 0.0)
    return result


def splat(acc, wsum, value, px, py, sx, sy, w, h, stddev):
    """Add the samples' values to the pixels (box filter: its own pixel; gaussian:
    Mitsuba's windowed gaussian, exp(-t^2 / (2 s^2)) - exp(-8) for |t| < 4 s, on
    every pixel centre near the sample); the image is acc / wsum."""
    if stddev is None:
        for c in range(3):
            acc[c] += np.bincount(py * w + px, weights=value[c], minlength=w * h)
        wsum += np.bincount(py * w + px, minlength=w * h)
        return
    radius, a = 4 * stddev, -1 / (2 * stddev**2)
    reach = range(-math.ceil(radius), math.ceil(radius) + 1)
    def weights(p, s, n):   # per offset o: pixel p + o, its weight (0 off the film)
        return [(p + o, np.where((p + o >= 0) & (p + o < n), np.maximum(
            0, np.exp(a * (p + o + 0.5 - s) ** 2) - math.exp(a * radius**2)), 0))
            for o in reach]
    wy = weights(py, sy, h)
    for tx, fx in weights(px, sx, w):
        for ty, fy in wy:
            wt = fx * fy
            keep = wt > 0                  # on the film and within the radius
            target, wt = (ty * w + tx)[keep], wt[keep]
            for c in range(3):
                acc[c] += np.bincount(target, weights=wt * value[c][keep], minlength=w * h)
            wsum += np.bincount(target, weights=wt, minlength=w * h)


def light_shader(scene, args, rng, settings):
    """direct's or path's value of camera rays (pyrender_direct.py, pyrender_path.py), with the scene's lights."""
    try:
        lights = scene_lights(scene, mi, dr, area_measure=args.bug == "area-pdf",
                              sphere_by_area=args.sphere_sampling == "area")
    except LightError as e:
        fail(f"{args.scene}: {args.integrator} does not render this scene: it has {e}")
    estimate = path if args.integrator == "path" else direct

    def offset(p, t):  # spawn_origin's, in numpy
        return np.full_like(t, BUG_OFFSET) if args.bug == "offset" else SPAWN_EPS * (np.max(np.abs(p), axis=0) + t)

    tracer = Tracer(scene, mi, dr, offset)

    def shade(ray, si, n_rays):
        if not lights:
            return np.zeros((3, n_rays))
        ray_o, ray_d = (np.array(v, dtype=np.float64) for v in (ray.o, ray.d))
        return estimate(tracer, lights, ray_o, ray_d, Hits.of(si, mi, dr), rng, settings, args.bug)
    return shade


def render(scene, args, rng, stddev, settings):
    w, h, spp = args.width, args.height, args.spp
    sensor = scene.sensors()[0]
    if args.integrator in ("direct", "path"):
        shader, max_rays = light_shader(scene, args, rng, settings), MAX_RAYS_DIRECT
    else:
        lights, env = emitters(scene)
        shader, max_rays = (lambda ray, si, n_rays: shade(scene, lights, env, args.integrator, ray, si, rng,
                                                          n_rays, args.bug)), MAX_RAYS
    npix = w * h
    k_max = max(1, max_rays // npix)             # samples per pixel per pass
    acc, wsum = np.zeros((3, npix)), np.zeros(npix)
    done = 0
    while done < spp:
        k = min(k_max, spp - done)
        n_rays = npix * k
        pix = np.repeat(np.arange(npix, dtype=np.int64), k)   # pixel-major
        px, py = pix % w, pix // w
        jitter = rng.random((2, n_rays))                        # uniform in the pixel
        sx, sy = px + jitter[0], py + jitter[1]
        pos = mi.Point2f(mi.Float((sx / w).astype(np.float32)), mi.Float((sy / h).astype(np.float32)))
        ray, _ = sensor.sample_ray(0.0, 0.5, pos, mi.Point2f(0.5))
        si = scene.ray_intersect(ray)
        value = shader(ray, si, n_rays)
        splat(acc, wsum, np.array(value, dtype=np.float64), px, py, sx, sy, w, h, stddev)
        done += k
    img = (acc / np.maximum(wsum, 1e-300)).T.reshape(h, w, 3)
    if args.bug == "bright":
        img *= 1.02
    return img.astype(np.float32)


def write_exr(path, images, seconds):
    """One image as R, G, B; several as the layers batch0.R/G/B, batch1.R/G/B, ..."""
    h, w, _ = images[0].shape
    layers = [""] if len(images) == 1 else [f"batch{k}." for k in range(len(images))]
    spec = oiio.ImageSpec(w, h, 3 * len(images), oiio.FLOAT)
    spec.channelnames = tuple(layer + c for layer in layers for c in "RGB")
    spec.attribute("pyrender.renderSeconds", float(seconds))
    spec.attribute("Software", VERSION)
    out = oiio.ImageOutput.create(path)
    if out is None or not out.open(path, spec):
        fail(f"cannot write {path!r}: {oiio.geterror()}")
    ok = out.write_image(np.ascontiguousarray(np.concatenate(images, axis=-1)))
    out.close()
    if not ok:
        fail(f"cannot write {path!r}: {out.geterror()}")


def refuse_non_diffuse(scene, path):
    """This renderer shades every surface as Mitsuba's diffuse: a glossy, specular or transmitting one is refused
    where the integrator reads the material, rather than rendered as something else."""
    other = (mi.BSDFFlags.Glossy, mi.BSDFFlags.Delta, mi.BSDFFlags.Transmission)
    for shape in scene.shapes():
        bsdf = shape.bsdf()
        if bsdf is not None and any(mi.has_flag(bsdf.flags(), flag) for flag in other):
            fail(f"{path}: the shape {shape.id() or '(unnamed)'} has a {bsdf.class_name()} BSDF: "
                 "this renderer models diffuse surfaces only")


def main(argv):
    version = argv == ["--version"]
    args = None if version else parse_args(argv)
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    global mi, dr, np, oiio
    import numpy as np
    import drjit as dr
    import mitsuba as mi
    import OpenImageIO as oiio
    if version:
        print(f"{VERSION} (Mitsuba {mi.__version__}, Dr.Jit {dr.__version__}, llvm_ad_rgb)")
        return 0
    try:
        mi.set_variant("llvm_ad_rgb")
    except Exception as e:  # noqa: BLE001 - any failure here is fatal
        fail(f"cannot set Mitsuba variant llvm_ad_rgb: {e}")
    if args.threads > 0:
        dr.set_thread_count(args.threads)
    xml, stddev, settings = scene_xml(args.scene, args.width, args.height, args.integrator)
    # Relative file names (meshes) resolve against the scene's folder.
    mi.file_resolver().prepend(os.path.dirname(os.path.abspath(args.scene)))
    try:
        scene = mi.load_string(xml)
    except Exception as e:  # noqa: BLE001 - Mitsuba raises RuntimeError and others
        fail(f"cannot load scene {args.scene!r}: {e}")
    if args.integrator in ("simple", "direct", "path"):
        refuse_non_diffuse(scene, args.scene)
    start = time.perf_counter()  # renderSeconds: rendering only, as docs/engines.md asks
    # Batch k draws from the stream (seed, k): independent of every other batch of this call and of other seeds.
    rngs = [np.random.default_rng(args.seed)] if args.batches == 1 else \
        [np.random.default_rng((args.seed, k)) for k in range(args.batches)]
    images = [render(scene, args, rng, stddev, settings) for rng in rngs]
    write_exr(args.output, images, time.perf_counter() - start)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
