"""An integrator is one C++ file: the test build's `albedo` (tests/cpp/albedo_integrator.cpp) reaches
the CLI's help and the Python module through the registry alone, and never the product build."""
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = ROOT / "build"
from tests.helpers.registered_integrators import PRODUCT, TEST_BUILD, name_list


def _help(binary: str) -> str:
    return subprocess.run([str(BUILD / binary), "--help"], capture_output=True, text=True, check=True).stdout


def test_product_cli_lists_the_product_integrators_only():
    text = _help("render")
    for name in PRODUCT:
        assert f"\n  {name} " in text
    assert "albedo" not in text


def test_test_build_cli_lists_albedo_from_its_one_file():
    text = _help("render_with_test_integrators")
    assert "\n  albedo    diffuse reflectance at the first hit" in text
    assert name_list(TEST_BUILD) in text  # --integrator's choices


def test_product_module_registry():
    import mcval_renderer
    assert mcval_renderer.integrators() == PRODUCT


def test_test_build_module_renders_albedo():
    """plane_ao's view is filled by a floor of reflectance 0.5: albedo's image is 0.5 everywhere."""
    code = ("import mcval_renderer as m, numpy as np; "
            "out = m.render('scenes/plane_ao.xml', spp=1, integrator='albedo', params={'res': '16'}); "
            "v = np.unique(out['mean']); print(m.integrators(), v.tolist())")
    env = dict(os.environ, PYTHONPATH=str(BUILD / "python-test"))
    res = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, check=True)
    assert res.stdout.strip() == f"{TEST_BUILD} [0.5]"
