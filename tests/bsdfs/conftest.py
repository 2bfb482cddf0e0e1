"""The BSDF tests' fixtures: Mitsuba's plugins (one child process per test process) and the compiled twin
libraries (our library and the checks' names: tests/helpers/bsdf_libraries.py)."""
from pathlib import Path

import pytest

from harness.engines.bsdf_library import BsdfLibrary
from harness.engines.mitsuba_bsdfs import MitsubaBsdfs
from tests.helpers.warp_libraries import build_warp_library

HERE = Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def mitsuba() -> MitsubaBsdfs:
    return MitsubaBsdfs()


@pytest.fixture(scope="session")
def twins(tmp_path_factory) -> BsdfLibrary:
    """tests/bsdfs/bsdf_twins.c: a Lambertian BSDF and its one-mistake twins."""
    return BsdfLibrary(build_warp_library(HERE / "bsdf_twins.c", tmp_path_factory.mktemp("twins")))


@pytest.fixture(scope="session")
def delta_twins(tmp_path_factory) -> BsdfLibrary:
    """tests/bsdfs/delta_twins.c: mirrors, glass and a plastic, each with one mistake."""
    return BsdfLibrary(build_warp_library(HERE / "delta_twins.c", tmp_path_factory.mktemp("delta")))


@pytest.fixture(scope="session")
def microfacet_twins(tmp_path_factory) -> BsdfLibrary:
    """tests/bsdfs/microfacet_twins.c: a Beckmann reflector and its microfacet mistakes."""
    return BsdfLibrary(build_warp_library(HERE / "microfacet_twins.c", tmp_path_factory.mktemp("microfacet")))
