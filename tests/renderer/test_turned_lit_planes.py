"""Turning or moving a whole lit-plane scene leaves its image mean alone, within its noise: the large floor
turned off the axes must not shadow itself (its hit points' rounding scales with its vertices), and a
shadow ray toward a light far from the origin must stop short of the light."""
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from harness.exr import read_layers
from harness.invariance.rewrite import rewrite
from tests.helpers.registered_integrators import PRODUCT

ROOT = Path(__file__).resolve().parents[2]
RENDER = shutil.which("render") or str(ROOT / "build" / "render")
SCENES = ROOT / "scenes"

LIT_PLANES = ("plane_rect_light", "plane_disk_light", "plane_sphere_light")
MOVES = {
    "turned": ("rotate", ((0.267, 0.535, 0.802), 37.0)),
    "moved": ("translate", (10.0, -20.0, 30.0)),
}
INTEGRATORS = [name for name in ("ao", "direct") if name in PRODUCT]
SPP, RES, SEED = 64, 32, 7
#: Standard errors the means may differ by (the two renders' errors combined).
TOLERANCE = 5.0


def _mean_and_error(scene: Path, integrator: str, out: Path) -> tuple[float, float]:
    """The image's mean and its standard error (from the variance of each pixel's mean)."""
    res = subprocess.run([RENDER, str(scene), "--integrator", integrator, "--spp", str(SPP), "--seed", str(SEED),
                          "-D", f"res={RES}", "-o", str(out), "-q"], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    layers, _ = read_layers(out)
    rgb, variance = layers["RGB"], layers["variance"]
    return float(rgb.mean()), float(np.sqrt(variance.sum()) / variance.size)


def _same_mean(a: tuple[float, float], b: tuple[float, float]) -> bool:
    return abs(a[0] - b[0]) <= TOLERANCE * float(np.hypot(a[1], b[1]))


@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("move", sorted(MOVES))
@pytest.mark.parametrize("name", LIT_PLANES)
def test_a_turned_or_moved_lit_plane_keeps_its_mean(tmp_path, name, move, integrator):
    source = SCENES / f"{name}.xml"
    kind, value = MOVES[move]
    moved = rewrite(source, tmp_path / f"{name}-{move}.xml", kind, value)
    before = _mean_and_error(source, integrator, tmp_path / "before.exr")
    after = _mean_and_error(moved, integrator, tmp_path / "after.exr")
    assert before[0] > 0.0
    assert _same_mean(before, after), f"{name} {move} under {integrator}: mean {after[0]} against {before[0]}"


#: A scene 2 % darker to each integrator: direct's floor reflects 2 % less; ao, which reads no material, is lit by
#: an environment 2 % darker than the radiance 1 it assumes without one.
DARKER = {"direct": ('<rgb name="reflectance" value="0.5, 0.5, 0.5"/>',
                     '<rgb name="reflectance" value="0.49, 0.49, 0.49"/>'),
          "ao": ("</scene>", '<emitter type="constant"><rgb name="radiance" value="0.98"/></emitter>\n</scene>')}


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_a_floor_two_percent_darker_is_told_apart(tmp_path, integrator):
    """The planted twin: the check sees a 2 % change of the mean (the fixed defects were 1 % to 99.9 %)."""
    source = SCENES / "plane_rect_light.xml"
    text = source.read_text()
    darker = tmp_path / "darker.xml"
    darker.write_text(text.replace(*DARKER[integrator]))
    assert darker.read_text() != text
    before = _mean_and_error(source, integrator, tmp_path / "before.exr")
    after = _mean_and_error(darker, integrator, tmp_path / "after.exr")
    assert not _same_mean(before, after)
