"""An integrator added without editing the harness: the test-only build's "albedo" (build/python-test,
build/render_with_test_integrators) with its entry in tests/plugins/integrators/, found through MCVAL_INTEGRATOR_PATH,
listed by `python -m harness integrators` and validated against Mitsuba's aov albedo."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers.registered_integrators import PRODUCT

ROOT = Path(__file__).resolve().parents[2]
TEST_MODULE = ROOT / "build" / "python-test"
TEST_RENDER = ROOT / "build" / "render_with_test_integrators"


@pytest.fixture(autouse=True)
def require_test_build():
    """`make build` builds the test-only targets; their absence is a failure, never a skip."""
    assert TEST_MODULE.is_dir() and TEST_RENDER.exists(), "build/python-test or build/render_with_test_integrators missing"


def harness(*args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(TEST_MODULE), "MCVAL_INTEGRATOR_PATH": str(ROOT / "tests" / "plugins" / "integrators"),
           "MCVAL_RENDER": str(TEST_RENDER)}
    return subprocess.run([sys.executable, "-m", "harness", *args], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=600)


def test_integrators_lists_albedo_with_its_entry():
    res = harness("integrators")
    assert res.returncode == 0, res.stderr
    row = next(line for line in res.stdout.splitlines() if line.strip().startswith("albedo"))
    assert "tests/plugins/integrators/albedo.py" in row and "aov(aovs=albedo:albedo)" in row, res.stdout
    for name in PRODUCT:
        assert any(line.strip().startswith(name) for line in res.stdout.splitlines())
    assert "no harness entry" not in res.stdout


@pytest.mark.slow
@pytest.mark.mitsuba
def test_albedo_passes_against_mitsuba(tmp_path):
    res = harness("images", "--only", "plane_point:albedo", "cornell_box:albedo", "--out", str(tmp_path))
    assert res.returncode == 0, res.stdout + res.stderr
    data = json.loads(((tmp_path / "latest").resolve() / "results.json").read_text())
    verdicts = {(e["scene"], e["integrator"]): e["pass"] for e in data["images"]}
    assert verdicts == {("plane_point", "albedo"): True, ("cornell_box", "albedo"): True}
    # plane_point has a closed form: the albedo is compared with it too.
    assert set(next(e for e in data["images"] if e["scene"] == "plane_point")["tests"]) == {"mitsuba", "analytic"}


@pytest.mark.slow
def test_albedo_gets_the_invariances_its_entry_says_apply(tmp_path):
    """Its entry says it is linear in reflectance only: the geometric invariances and reflectance run, light
    does not (no emitter changes an albedo)."""
    res = harness("invariance", "--only", "plane_point:albedo", "--no-mitsuba", "--out", str(tmp_path))
    assert res.returncode == 0, res.stdout + res.stderr
    data = json.loads(((tmp_path / "latest").resolve() / "results.json").read_text())["invariance"]
    ran = {c["invariance"] for c in data["cells"] if c["integrator"] == "albedo"}
    assert ran == {"scale", "rotate", "translate", "reflectance"}
    assert all(c["pass"] for c in data["cells"])
    assert "albedo" in data["invariances"]["reflectance"]["integrators"]
    assert "albedo" not in data["invariances"]["light"]["integrators"]


@pytest.mark.slow
@pytest.mark.mitsuba
def test_albedo_is_benchmarked_against_mitsuba(tmp_path):
    # cornell: no closed form, so the errors are measured against a Mitsuba render, not a long exact one.
    res = harness("bench", "--only", "cornell:albedo", "--engines", "mcval", "mitsuba", "--same-sampler",
                  "--max-spp", "2", "--runs", "2", "--throughput-runs", "0", "--seed-runs", "0", "--out", str(tmp_path))
    assert res.returncode == 0, res.stdout + res.stderr
    data = json.loads(((tmp_path / "latest").resolve() / "results.json").read_text())
    [case] = data["speed"]
    assert (case["scene"], case["integrator"]) == ("cornell", "albedo")
    assert set(case["efficiency"]) == {"mcval/independent", "mitsuba/independent"}
