"""A case that breaks a stage fails itself in one line and the run goes on: the engine under test refusing a
file (before any reference is rendered for it), an exception no stage foresaw (its traceback kept for the
run's log), and a case whose report cannot be written."""
import shutil

import numpy as np
import pytest

from harness.engines.base import Engine, RenderFailed, RenderResult
from harness.images.run import run_images
from harness.images.suite import SCENES_DIR, select_cases
from harness.images.user_scenes import prepare_scenes
from tests.helpers.registered_integrators import PRODUCT


class Flat(Engine):
    """A flat 0.5 image; a scene named in `refuse` is refused as a loader would, one in `broken` comes back
    the wrong size (the comparison then raises)."""

    name = "flat"

    def __init__(self, refuse=(), broken=()):
        self.refuse, self.broken, self.calls = refuse, broken, []

    def version(self) -> str:
        return "flat"

    def render(self, scene, integrator, spp, batches, seed, params=None):
        self.calls.append(scene)
        if any(scene.endswith(f"/{name}.xml") for name in self.refuse):
            raise RenderFailed(f"error: {scene}:12: <shape>: not loaded")
        size = 4 if any(scene.endswith(f"/{name}.xml") for name in self.broken) else 8
        images = 0.5 + 0.01 * np.random.default_rng(seed).standard_normal((batches, size, size, 3))
        return RenderResult(self.name, scene, integrator, spp, seed, images.astype(np.float32), {"total": 0.0})


def _cases(tmp_path, names):
    folder = tmp_path / "in"
    folder.mkdir()
    for name in names:
        shutil.copy(SCENES_DIR / "plane_point.xml", folder / f"{name}.xml")
    user = prepare_scenes([folder], tmp_path / "cache", 8)
    return select_cases([f"{n}:normals" for n in names], user=user), folder


def test_a_file_the_tested_engine_refuses_costs_no_reference_render(tmp_path):
    cases, folder = _cases(tmp_path, ["good", "refused"])
    tested, reference = Flat(refuse=("refused",)), Flat()
    results, _ = run_images(cases, tested, reference)
    by_scene = {r.case.scene: r for r in results}
    assert by_scene["good"].error is None
    error = by_scene["refused"].error
    assert error.startswith("flat render: error: ") and f"{folder / 'refused.xml'}:" in error and "\n" not in error
    assert not any(call.endswith("/refused.xml") for call in reference.calls)
    assert any(call.endswith("/good.xml") for call in reference.calls)


def test_an_unforeseen_exception_fails_its_case_in_one_line_with_its_traceback(tmp_path):
    cases, _ = _cases(tmp_path, ["good", "broken"])
    results, _ = run_images(cases, Flat(broken=("broken",)), Flat())
    by_scene = {r.case.scene: r for r in results}
    assert by_scene["good"].error is None and not by_scene["good"].traceback
    broken = by_scene["broken"]
    assert broken.error.startswith("internal error: ") and "\n" not in broken.error
    assert "Traceback (most recent call last)" in broken.traceback


def test_a_case_whose_report_cannot_be_written_fails_alone(tmp_path, monkeypatch):
    import harness.report.image_outputs as outputs
    from harness.report.image_html import entry_html

    cases, _ = _cases(tmp_path, ["good", "unreported"])
    results, alpha = run_images(cases, Flat(), Flat())

    def entry(r, run=None):
        if r.case.scene == "unreported":
            raise OverflowError("a value the page cannot show")
        return entry_html(r, run)

    monkeypatch.setattr(outputs, "entry_html", entry)
    payload = outputs.write_image_outputs(tmp_path / "run", results, alpha, None, {}, None)
    by_scene = {e["scene"]: e for e in payload["images"]}
    assert by_scene["unreported"]["pass"] is False
    assert by_scene["unreported"]["error"] == "report: OverflowError: a value the page cannot show"
    assert by_scene["good"]["error"] is None and (tmp_path / "run" / "report.html").exists()


@pytest.mark.mitsuba
def test_mitsubas_load_error_names_the_line_of_the_users_file(tmp_path):
    """Mitsuba loads the prepared copy, edited per integrator (emitters dropped, the integrator replaced): its
    error's line is the user's, after all of those edits."""
    from harness.engines.mitsuba import MitsubaEngine

    folder = tmp_path / "in"
    folder.mkdir()
    text = (SCENES_DIR / "plane_point.xml").read_text().replace("</scene>", "\n\n    <foo/>\n</scene>")
    (folder / "late.xml").write_text(text)
    line = text[:text.index("<foo/>")].count("\n") + 1
    user = prepare_scenes([folder], tmp_path / "cache", 8)
    results, _ = run_images(select_cases(["late"], user=user), Flat(), MitsubaEngine())
    assert len(results) == len(PRODUCT)
    for r in results:
        assert f"in {folder / 'late.xml'}:{line}: " in r.error and "<foo>" in r.error, r.error
