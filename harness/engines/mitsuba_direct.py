"""`mcval_direct`: Mitsuba's `direct` integrator with the ray offset taken to its limit.

Mitsuba spawns a secondary ray (1 + max|p|) * 1500 float epsilons off the surface, 2e-4 at unit scale. Where
a shadow ray grazes a fine mesh that offset decides the pixel: on `highpoly` under `simple` it lets up to 2.6x
the light through at the terminator (docs/findings.md). Visibility at a surface point is the limit as the
offset goes to 0, so the reference renders with the smallest offset that still cannot re-hit its own surface:
64 float epsilons of (max|p| + the scene's smallest shape size). It grows with the position's magnitude (its
rounding error) and with the scene's scale, so scaling the scene does not change the image.

Everything else is `direct` as Mitsuba computes it (direct.cpp): the emitter hit by the camera ray unless
`hide_emitters`, `emitter_samples` emitter samples and `bsdf_samples` BSDF samples combined by the power
heuristic, one sample count of each per pixel sample. Its three properties are read as `direct` reads them;
`offset_epsilons` (default 64) and `offset_floor` (default: the smallest shape's size) set the offset,
`offset_epsilons` * 2^-24 * (max|p| + `offset_floor`): 1500 and 1 give Mitsuba's own, and its image.
"""
from __future__ import annotations

PLUGIN = "mcval_direct"
#: The offset per unit of (max|p| + smallest shape size), in float epsilons (2^-24).
OFFSET_EPSILONS = 64
#: How Mitsuba shortens a shadow ray towards its target (math::ShadowEpsilon, single precision).
SHADOW_EPSILON = 1500 * 10 * 2.0**-24

_registered: set[str] = set()


def smallest_shape_size(scene) -> float:
    """Half the largest side of the smallest shape's bounding box (0 for a scene without shapes)."""
    import drjit as dr
    sizes = [0.5 * float(dr.max(shape.bbox().extents())) for shape in scene.shapes()]
    sizes = [s for s in sizes if s > 0]  # a degenerate shape, which no ray hits, sets no floor
    return min(sizes) if sizes else 0.0


def register(mi) -> None:
    """Register `mcval_direct` for Mitsuba's current variant (a plugin is registered per variant)."""
    if mi.variant() in _registered:
        return
    import drjit as dr

    def mis_weight(a, b):
        a2 = dr.square(a)
        return dr.select(a > 0, a2 / (a2 + dr.square(b)), 0.0)

    class TightDirect(mi.SamplingIntegrator):
        def __init__(self, props):
            super().__init__(props)
            self.hide_emitters = props.get("hide_emitters", False)
            self.emitter_samples = int(props.get("emitter_samples", 1))
            self.bsdf_samples = int(props.get("bsdf_samples", 1))
            if self.emitter_samples + self.bsdf_samples == 0:
                raise ValueError("mcval_direct: emitter_samples + bsdf_samples must be > 0")
            total = self.emitter_samples + self.bsdf_samples
            self.weight_lum = 1.0 / max(self.emitter_samples, 1)
            self.weight_bsdf = 1.0 / max(self.bsdf_samples, 1)
            self.frac_lum = self.emitter_samples / total
            self.frac_bsdf = self.bsdf_samples / total
            self.epsilons = float(props.get("offset_epsilons", OFFSET_EPSILONS))
            self.floor = float(props["offset_floor"]) if "offset_floor" in props else None

        def sample(self, scene, sampler, ray, medium=None, active=True):
            floor = self.floor if self.floor is not None else smallest_shape_size(scene)
            si = scene.ray_intersect(ray, active)

            def origin(d):
                """si.p moved off its surface along the geometric normal, to the side d leaves by."""
                n = dr.select(dr.dot(si.n, d) >= 0, si.n, -si.n)
                return si.p + n * (self.epsilons * 2.0**-24 * (dr.max(dr.abs(si.p)) + floor))

            result = mi.Spectrum(0.0)
            if not self.hide_emitters:
                result += si.emitter(scene, active).eval(si, active)
            active = active & si.is_valid()
            bsdf = si.bsdf(ray)
            ctx = mi.BSDFContext()
            for _ in range(self.emitter_samples):
                ds, emitter_val = scene.sample_emitter_direction(si, sampler.next_2d(active), False, active)
                active_e = active & (ds.pdf != 0.0)
                o = origin(ds.d)
                to_target = ds.p - o
                dist = dr.norm(to_target)
                shadow = mi.Ray3f(o, to_target / dist)
                shadow.maxt = dist * (1.0 - SHADOW_EPSILON)  # Ray3f(o, d, x) would read x as the time
                active_e &= ~scene.ray_test(shadow, active_e)
                bsdf_val, bsdf_pdf = bsdf.eval_pdf(ctx, si, si.to_local(ds.d), active_e)
                mis = dr.select(ds.delta, 1.0, mis_weight(ds.pdf * self.frac_lum, bsdf_pdf * self.frac_bsdf))
                result += dr.select(active_e, mis * self.weight_lum * bsdf_val * emitter_val, 0.0)
            for _ in range(self.bsdf_samples):
                # Mitsuba's build evaluates the arguments of bsdf->sample() right to left: the 2D sample
                # first, so that both draw the same numbers for the same seed.
                sample2 = sampler.next_2d(active)
                bs, bsdf_val = bsdf.sample(ctx, si, sampler.next_1d(active), sample2, active)
                d = si.to_world(bs.wo)
                si_bsdf = scene.ray_intersect(mi.Ray3f(origin(d), d), active)
                emitter = si_bsdf.emitter(scene, active)
                active_b = active & (emitter != None)  # noqa: E711 (a Dr.Jit pointer array)
                emitter_val = emitter.eval(si_bsdf, active_b)
                delta = mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
                ds = mi.DirectionSample3f(scene, si_bsdf, si)
                emitter_pdf = dr.select(delta, 0.0, scene.pdf_emitter_direction(si, ds, active_b & ~delta))
                mis = mis_weight(bs.pdf * self.frac_bsdf, emitter_pdf * self.frac_lum)
                result += dr.select(active_b, bsdf_val * emitter_val * mis * self.weight_bsdf, 0.0)
            return result, active, []

        def aov_names(self):
            return []

        def to_string(self):
            return (f"{PLUGIN}[emitter_samples={self.emitter_samples}, bsdf_samples={self.bsdf_samples}, "
                    f"offset_epsilons={self.epsilons}, offset_floor={self.floor}]")

    mi.register_integrator(PLUGIN, lambda props: TightDirect(props))
    _registered.add(mi.variant())
