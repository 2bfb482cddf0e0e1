"""The child side of Mitsuba's BSDFs (harness/engines/mitsuba_bsdfs.py): a plugin made with mi.load_dict and its
eval, pdf and sample called on numpy arrays, in a process of its own, in the local frame (z the normal)."""
from __future__ import annotations

import numpy as np

_mi = None
_made: dict[str, object] = {}


def _bsdf(spec: dict):
    global _mi
    if _mi is None:
        from harness.engines.mitsuba import load_mitsuba

        _mi = load_mitsuba()
        import drjit as dr

        # One thread: the matrix runs a row per core, each with a child of its own, and threads of every child on
        # every core only compete (about 3 s of CPU less over the default matrix).
        dr.set_thread_count(1)
    key = repr(sorted(spec.items()))
    if key not in _made:
        _made[key] = _mi.load_dict(spec)
    return _made[key]


def _vectors(a: np.ndarray):
    return _mi.Vector3f(*(np.ascontiguousarray(a[:, i], np.float32) for i in range(3)))


def _interaction(wi: np.ndarray):
    import drjit as dr

    si = dr.zeros(_mi.SurfaceInteraction3f, len(wi))
    si.n = _mi.Normal3f(0.0, 0.0, 1.0)
    si.sh_frame = _mi.Frame3f(si.n)
    si.wi = _vectors(wi)
    return si


def _width(a, n: int) -> np.ndarray:
    """a as n floats: a plugin that answers a constant (a mirror's pdf: 0) gives Dr.Jit's array of width 1."""
    a = np.asarray(a, np.float32)
    return np.full(n, a[0], np.float32) if a.shape == (1,) and n != 1 else a


def eval_or_pdf(spec: dict, kind: str, wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """The plugin's eval (its first channel) or pdf at n rows of wi, wo: (n,) float32."""
    bsdf = _bsdf(spec)
    out = getattr(bsdf, kind)(_mi.BSDFContext(), _interaction(wi), _vectors(wo))
    return _width(np.asarray(out, np.float32)[0] if kind == "eval" else out, len(wo))


def sample(spec: dict, wi: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The plugin's sample at n rows of wi and u (the third uniform chooses a lobe): wo, weight, pdf, with weight
    and pdf 0 where it sampled nothing and pdf infinite on a delta lobe (as include/mcval_bsdfs.h has it)."""
    bsdf = _bsdf(spec)
    u = np.asarray(u, np.float32)
    bs, weight = bsdf.sample(_mi.BSDFContext(), _interaction(wi), _mi.Float(u[:, 2]), _mi.Point2f(u[:, 0], u[:, 1]))
    n = len(u)
    wo = np.stack([_width(c, n) for c in (bs.wo.x, bs.wo.y, bs.wo.z)], axis=1)
    weight = _width(np.asarray(weight, np.float32)[0], n)
    drawn = (weight != 0) & np.isfinite(weight)
    delta = _width(_mi.has_flag(bs.sampled_type, _mi.BSDFFlags.Delta), n) != 0  # Mitsuba's pdf there is 1
    pdf = np.where(delta, np.float32(np.inf), _width(bs.pdf, n))
    return wo, np.where(drawn, weight, 0.0), np.where(drawn, pdf, 0.0)
