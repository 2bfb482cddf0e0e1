"""examples/bsdfs/nori_microfacet.c, built as its README says, passes the BSDF matrix at 0, 60, 80 and 89 degrees, at two
parameter sets and seeds 0 and 1."""
import json
from pathlib import Path

import pytest

from harness.cli import main
from tests.helpers.warp_libraries import build_warp_library

SOURCE = Path(__file__).resolve().parents[2] / "examples" / "bsdfs" / "nori_microfacet.c"


@pytest.fixture(scope="module")
def library(tmp_path_factory) -> Path:
    return build_warp_library(SOURCE, tmp_path_factory.mktemp("nori"))


@pytest.mark.parametrize("seed", [0, 1])
def test_the_example_microfacet_passes(library, tmp_path, seed):
    out = tmp_path / "r"
    code = main(["bsdfs", "--bsdf-library", str(library), "--bsdf", "microfacet",
                 "microfacet:alpha=0.6,kd=0.6,ks=0.4,int_ior=1.8", "--angles", "0", "60", "80", "89", "--samples", "100000", "--seed", str(seed), "--out",
                 str(out)])
    rows = json.loads((out / "latest" / "results.json").read_text())["bsdfs"]
    assert code == 0 and len(rows) == 8 and all(r["pass"] for r in rows), [r for r in rows if not r["pass"]]
