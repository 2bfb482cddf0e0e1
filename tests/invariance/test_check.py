"""The invariance check catches a known-wrong twin and passes a correct engine over several seeds."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from harness.integrators import entry

from harness.engines.base import Engine, RenderResult
from harness.invariance.check import InvarianceCase, run_invariances
from harness.invariance.findings import invariance_payload
from harness.invariance.suite import select
from harness.invariance.variants import invariance

SCENES = Path(__file__).resolve().parents[2] / "scenes"
RES = 32


class LightTwin(Engine):
    """Our renderer, but 2 % too bright whenever the scene's lights were doubled (variant files are named
    <scene>.<invariance>.<n>.xml by the check)."""

    name = "light-twin"

    def __init__(self) -> None:
        from harness.engines.mcval import McvalEngine
        self._mcval = McvalEngine()

    def version(self) -> str:
        return "mcval x1.02 under doubled lights"

    def render(self, scene, integrator, spp, batches, seed, params=None) -> RenderResult:
        out = self._mcval.render(scene, integrator, spp, batches, seed, params)
        if ".light." in Path(scene).name:
            out.batches = out.batches * np.float32(1.02)
        return out


def _cases(*keys: str) -> list[InvarianceCase]:
    return [InvarianceCase(SCENES / f"{k.split(':')[0]}.xml", k.split(":")[1], 16, RES) for k in keys]


def test_a_two_percent_light_error_is_caught():
    from harness.engines.mcval import McvalEngine

    invariances = [invariance("light"), invariance("reflectance")]
    cells, _ = run_invariances([McvalEngine(), LightTwin()], _cases("plane_point:simple", "sphere_plane:ao"),
                               invariances, seed=3)
    twin = {(c.invariance, c.case.key): c for c in cells if c.engine == "light-twin"}
    for key in ("plane_point:simple", "sphere_plane:ao"):
        assert not twin["light", key].passed
        assert twin["light", key].worst_ratio == pytest.approx(1.02, abs=0.005)
        assert twin["reflectance", key].passed
    # The twin as a reference: its breaks are findings, and the run passes on mcval.
    payload = invariance_payload(cells, 1e-3, "mcval", {})
    assert payload["pass"] and len(payload["findings"]) == 2
    assert payload["findings"][0].startswith("reference light-twin breaks light on plane_point:simple")
    # The twin under test: the run fails.
    assert not invariance_payload(cells, 1e-3, "light-twin", {})["pass"]


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_renderer_keeps_the_invariances(seed):
    from harness.engines.mcval import McvalEngine

    cases = _cases("plane_point:simple", "plane_point:ao", "sphere_plane:simple", "sphere_plane:normals")
    names = ["rotate", "translate", "light", "reflectance"]
    cells, _ = run_invariances([McvalEngine()], cases, [invariance(n) for n in names], seed=seed)
    assert cells and all(c.passed for c in cells), [(c.case.key, c.invariance, c.worst_ratio) for c in cells
                                                    if not c.passed]


def test_rotated_normals_are_rotated_back():
    """Without the rotation back, a rotated scene's normals image differs: the check must know it."""
    from harness.engines.mcval import McvalEngine

    rotate = invariance("rotate")
    cells, _ = run_invariances([McvalEngine()], _cases("sphere_plane:normals"), [rotate], seed=5)
    assert cells[0].passed
    variant = rotate.variants[0]
    n = np.array([[[[0.0, 1.0, 0.0]]]])
    assert not np.allclose(variant.expected(entry("normals"), n), n)
    assert np.allclose(variant.expected(entry("simple"), n), n)


def test_select_narrows_and_refuses_unknown_names():
    cases, invariances = select(["crevice", "ao", "scale"])
    assert [c.key for c in cases] == ["crevice:ao"] and [i.name for i in invariances] == ["scale"]
    cases, _ = select(["cornell:normals"])
    assert [c.key for c in cases] == ["cornell:normals"]
    with pytest.raises(ValueError, match="nonsense"):
        select(["nonsense"])


def test_by_default_every_scene_runs_with_every_integrator_that_applies():
    from harness.images.suite import scene_names

    keys = {c.key for c in select(None)[0]}
    for scene in scene_names() + scene_names("real"):
        # ao sees no environment from inside the furnace (not applicable there).
        assert f"{scene}:normals" in keys and (f"{scene}:ao" in keys or scene == "furnace")
    assert "cornell_box:simple" not in keys  # no point light
    with pytest.raises(ValueError, match="not applicable"):
        select(["cornell_box:simple"])


def test_ao_without_a_constant_emitter_keeps_its_fixed_ambient_under_doubled_lights():
    light = invariance("light").variants[0]
    image = np.full((1, 2, 2, 3), 0.4)
    assert np.allclose(light.expected(entry("ao"), image, has_environment=True), 0.2)
    assert np.allclose(light.expected(entry("ao"), image, has_environment=False), 0.4)
    assert np.allclose(light.expected(entry("simple"), image, has_environment=False), 0.2)


class NeverRenders(Engine):
    """An engine that fails the test if it is asked to render."""

    name = "never"

    def version(self) -> str:
        return "never"

    def render(self, scene, integrator, spp, batches, seed, params=None) -> RenderResult:
        raise AssertionError(f"rendered {scene}")


def test_a_scene_that_cannot_be_rendered_fails_its_cells_with_why(tmp_path):
    from harness.images.user_scenes import prepare_scenes
    (tmp_path / "quad.obj").write_text("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\n")
    (tmp_path / "paths.xml").write_text('<scene>\n<integrator type="normals"/>\n<mesh type="obj"><string '
                                        'name="filename" value="quad.obj"/></mesh><camera type="thinlens"/>'
                                        '\n</scene>\n')
    user = prepare_scenes([tmp_path / "paths.xml"], tmp_path / "cache", RES)
    cases, invariances = select(["paths:normals", "scale"], user=user)
    assert cases[0].problem.startswith(f"{tmp_path / 'paths.xml'}:3: <camera type=\"thinlens\">")
    cells, _ = run_invariances([NeverRenders()], cases, invariances, seed=0)
    assert [c.base_error for c in cells] == [cases[0].problem]
    assert _cases("plane_point:normals")[0].problem == ""


class Elsewhere(Engine):
    """mcval, said to render in another process (renders overlap the comparisons), failing where told: the
    base when `fail_base`, a variant whose file name holds `fail`. It counts its renders. Named as mcval, so
    that it draws mcval's seeds."""

    name = "mcval"
    renders_elsewhere = True

    def __init__(self, fail_base: bool = False, fail: str = "") -> None:
        from harness.engines.mcval import McvalEngine
        self._mcval, self.fail_base, self.fail, self.rendered = McvalEngine(), fail_base, fail, []

    def version(self) -> str:
        return "elsewhere"

    def render(self, scene, integrator, spp, batches, seed, params=None) -> RenderResult:
        from harness.engines.base import RenderFailed
        self.rendered.append(Path(scene).name)
        if (self.fail_base and "." not in Path(scene).stem) or (self.fail and self.fail in Path(scene).name):
            raise RenderFailed(f"told to fail on {Path(scene).name}")
        return self._mcval.render(scene, integrator, spp, batches, seed, params)


def test_overlapped_renders_give_the_serial_cells_and_keep_failures_apart():
    from harness.engines.mcval import McvalEngine

    cases, invariances = _cases("plane_point:simple"), [invariance("scale"), invariance("light")]
    serial, _ = run_invariances([McvalEngine(in_process=True)], cases, invariances, seed=2)
    elsewhere = Elsewhere(fail="scale.1")
    overlapped, _ = run_invariances([elsewhere], cases, invariances, seed=2)
    assert elsewhere.rendered == ["plane_point.xml", "plane_point.scale.0.xml", "plane_point.scale.1.xml",
                                  "plane_point.light.0.xml"]
    failed = overlapped[0].variants[1]
    assert failed.error == "told to fail on plane_point.scale.1.xml" and failed.status == "fail"
    for mine, theirs in zip(overlapped, serial):
        kept = [v.to_json() for v in mine.variants if v.error is None]
        assert kept == [v.to_json() for v in theirs.variants if v.variant.label != "x1000"]
    # Without a base no variant is rendered, and every cell says why.
    no_base = Elsewhere(fail_base=True)
    cells, _ = run_invariances([no_base], cases, invariances, seed=2)
    assert no_base.rendered == ["plane_point.xml"]
    assert [c.base_error for c in cells] == ["told to fail on plane_point.xml"] * 2


def test_a_variant_of_one_image_where_the_base_varies_is_not_independent():
    """Base and variant are one engine's one estimator: a variant whose batches are one image, where the base's
    vary, did not use its seed; a black variant is left to the comparison, and two noiseless sides pass."""
    from harness.comparison.summary import summarize
    from harness.invariance.check import variant_alike

    rng = np.random.default_rng(7)
    p = np.linspace(0.05, 0.95, RES)[None, :, None] * np.ones((RES, 1, 3))
    noisy = summarize(rng.binomial(32, p, size=(8, RES, RES, 3)) / 32)
    one = summarize(np.repeat(rng.binomial(32, p, size=(1, RES, RES, 3)) / 32, 8, axis=0))
    assert variant_alike(one, noisy).startswith("batches not independent: all 8 variant batches are the same image, "
                                                "where the base's vary")
    assert variant_alike(noisy, noisy) is None and variant_alike(one, one) is None
    assert variant_alike(summarize(np.zeros((8, RES, RES, 3))), noisy) is None
