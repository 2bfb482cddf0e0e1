"""BSDFs through the C ABI of include/mcval_bsdfs.h (harness/engines/bsdf_library.py): ours (build/libmcval_bsdfs.so)
and a C library built as a user would, each function called in the library's own process; a crash, a write past
the output or a missing function fails that BSDF with one line, and the library's other BSDFs go on."""
from pathlib import Path

import numpy as np
import pytest

from harness.engines.bsdf_library import BsdfLibrary, BsdfUnavailable
from harness.engines.python_child import ChildFailed
from tests.helpers.warp_libraries import build_warp_library

ROOT = Path(__file__).resolve().parents[2]
OURS = ROOT / "build" / "libmcval_bsdfs.so"
SOURCES = Path(__file__).parent / "bsdf_libraries"


@pytest.fixture(scope="module")
def misbehaving(tmp_path_factory) -> BsdfLibrary:
    return BsdfLibrary(build_warp_library(SOURCES / "misbehaving_bsdfs.c", tmp_path_factory.mktemp("bsdfs")))


def _directions(n: int, seed: int) -> np.ndarray:
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


@pytest.mark.parametrize("rho", [0.3, 0.9])
def test_our_diffuse_is_lambertian_and_its_weight_is_its_albedo(rho):
    diffuse = BsdfLibrary(OURS).functions("diffuse", {"reflectance": rho})
    wi, u = _directions(4000, 1), np.random.default_rng(2).random((4000, 3))
    wo, weight, pdf = diffuse.sample(wi, u)
    above = wi[:, 2] > 0
    assert np.allclose(np.linalg.norm(wo, axis=1), 1, atol=1e-6) and np.all(wo[above, 2] >= 0)
    assert np.all(weight[~above] == 0) and np.all(pdf[~above] == 0)
    assert np.allclose(weight[above], rho) and np.allclose(pdf[above], wo[above, 2] / np.pi, rtol=1e-6)
    both = above & (wo[:, 2] > 0)
    assert np.allclose(diffuse.eval(wi, wo)[both], rho / np.pi * wo[both, 2], rtol=1e-6)
    assert np.allclose(diffuse.pdf(wi, wo)[both], pdf[both], rtol=1e-6)
    assert diffuse.label == f"diffuse reflectance={rho:g}"


def test_a_user_library_lists_its_bsdfs_and_their_parameters(misbehaving):
    assert misbehaving.names == ["arrayed", "crash", "lambert", "nullparams", "overrun", "partial", "spaced",
                                 "trailing"]
    assert misbehaving.parameters("lambert") == ["albedo"] and misbehaving.parameters("crash") == []
    with pytest.raises(BsdfUnavailable, match="exports partial without bsdf_partial_sample"):
        misbehaving.parameters("partial")
    with pytest.raises(BsdfUnavailable, match="exports no BSDF ggx"):
        misbehaving.parameters("ggx")
    with pytest.raises(ValueError, match="lambert takes the parameters albedo: alpha unknown; albedo not given"):
        misbehaving.functions("lambert", {"alpha": 0.1})


def test_a_parameter_list_is_read_or_refused_in_one_line(misbehaving):
    """An array where the ABI has a pointer is read as the string it holds (it used to hide every BSDF of the
    library); names separated by a space, a trailing comma or a NULL pointer are refused, naming the symbol."""
    assert misbehaving.parameters("arrayed") == ["albedo"]
    _, weight, _ = misbehaving.functions("arrayed", {"albedo": 0.5}).sample(_directions(10, 5),
                                                                           np.full((10, 3), 0.5))
    assert set(weight) <= {0.0, 0.5}
    for name, why in [("spaced", "bsdf_spaced_params is 'albedo exponent': expected names"),
                      ("trailing", "bsdf_trailing_params is 'albedo,': expected names"),
                      ("nullparams", 'bsdf_nullparams_params is NULL: give "" for a BSDF without parameters')]:
        with pytest.raises(BsdfUnavailable, match=f"^libmisbehaving_bsdfs.so: {why}"):
            misbehaving.parameters(name)


def test_a_crash_or_an_overrun_fails_its_call_alone(misbehaving):
    wi, u = _directions(100, 3), np.random.default_rng(4).random((100, 3))
    with pytest.raises(ChildFailed) as crash:
        misbehaving.functions("crash", {}).sample(wi, u)
    assert crash.value.reason == "libmisbehaving_bsdfs.so: bsdf_crash_sample (crash) was killed by SIGSEGV"
    with pytest.raises(ChildFailed) as overrun:
        misbehaving.functions("overrun", {"albedo": 0.5}).eval(wi, wi)
    assert overrun.value.reason == ("libmisbehaving_bsdfs.so: bsdf_overrun_eval (overrun albedo=0.5) wrote past the "
                                    "end of its value (100 rows, 1 float each)")
    _, weight, _ = misbehaving.functions("lambert", {"albedo": 0.5}).sample(wi, u)  # the library, loaded again
    assert np.all(weight[wi[:, 2] > 0] == 0.5)
