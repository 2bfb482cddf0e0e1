"""A reference engine's stored invariance cells: read back as written, refused when stale or damaged, used
instead of rendering, and current in references/ for every default case."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from harness.engines.base import Engine
from harness.images.references import REFERENCE_SEED
from harness.invariance.check import applicable, family_alpha, run_invariances
from harness.invariance.findings import invariance_payload
from harness.invariance.stored import check_sha256, read_cells, stored_cells, stored_path, write_cells
from harness.invariance.suite import select
from harness.statistics.constants import IMAGE_BATCHES

KEY = "plane_point:normals"


@pytest.fixture(scope="module")
def default():
    """The default cases and invariances, the suite's level, and the one case rendered here."""
    cases, invariances = select(None)
    case = next(c for c in cases if c.key == KEY)
    return cases, invariances, family_alpha(cases, invariances), case


@pytest.fixture(scope="module")
def written(default, mitsuba, tmp_path_factory):
    """The case's cells by Mitsuba, rendered at the references' seed and stored in a folder of its own."""
    cases, invariances, alpha, case = default
    cells, _ = run_invariances([mitsuba], [case], invariances, REFERENCE_SEED, alpha=alpha)
    folder = tmp_path_factory.mktemp("store")
    path = write_cells(mitsuba, case, applicable(invariances, case), cells, alpha, IMAGE_BATCHES, folder)
    return cells, folder, path


def _read(mitsuba, default, folder, alpha=None, batches=IMAGE_BATCHES, check=None):
    _, invariances, suite_alpha, case = default
    return read_cells(mitsuba, case, applicable(invariances, case), suite_alpha if alpha is None else alpha,
                      batches, check or check_sha256(), folder)


def test_cells_read_back_as_written(written, mitsuba, default):
    cells, folder, path = written
    assert path == folder / "mitsuba" / "plane_point" / "invariance-normals.json"
    back, why = _read(mitsuba, default, folder)
    assert why == "" and [c.to_json() for c in back] == [c.to_json() for c in cells]
    assert [c.passed for c in back] == [c.passed for c in cells]
    assert invariance_payload(back, 1e-3, "mcval", {})["cells"] == invariance_payload(cells, 1e-3, "mcval", {})["cells"]


@pytest.mark.parametrize("change, what", [({"alpha": 1e-4}, "alpha"), ({"batches": 4}, "batches"),
                                          ({"check": "0" * 64}, "check_sha256")])
def test_stale_cells_are_refused_with_what_changed(written, mitsuba, default, change, what):
    _, folder, path = written
    cells, why = _read(mitsuba, default, folder, **change)
    assert cells is None and why == f"{path}: stale ({what} changed)"  # outside the project: named whole


def _edited(path: Path, tmp_path: Path, edit) -> Path:
    """A copy of the store with the case's file edited by `edit` (text -> text)."""
    folder = tmp_path / "store"
    target = folder / path.relative_to(path.parents[2])
    target.parent.mkdir(parents=True)
    target.write_text(edit(path.read_text()))
    return folder


def test_an_edited_cell_is_refused(written, mitsuba, default, tmp_path):
    _, _, path = written
    meta = json.loads(path.read_text())
    meta["cells"][0]["pass"] = not meta["cells"][0]["pass"]
    folder = _edited(path, tmp_path, lambda _: json.dumps(meta))
    cells, why = _read(mitsuba, default, folder)
    assert cells is None and why.endswith("its cells do not match content_sha256 (edited or damaged)")


@pytest.mark.parametrize("edit, what", [(lambda t: t[: len(t) // 2], "JSONDecodeError"),
                                        (lambda t: "[]", "TypeError"),
                                        (lambda t: t.replace('"provenance"', '"origin"'), "KeyError")])
def test_a_damaged_file_is_refused_in_one_line(written, mitsuba, default, tmp_path, edit, what):
    _, _, path = written
    folder = _edited(path, tmp_path, edit)
    cells, why = _read(mitsuba, default, folder)
    assert cells is None and "not a stored cell file" in why and what in why and "\n" not in why


def test_a_missing_file_and_a_user_scene_are_rendered(mitsuba, default, tmp_path):
    cases, invariances, alpha, case = default
    cells, why = _read(mitsuba, default, tmp_path)
    assert cells is None and why.endswith("not stored")
    user = type(case)(tmp_path / "mine.xml", case.integrator, case.spp, case.res)
    assert stored_path(mitsuba, user) is None


class Refuses(Engine):
    """An engine that must not render: its cells are stored."""

    name = "mitsuba"

    def version(self) -> str:
        return "refuses"

    def render(self, *args, **kwargs):
        raise AssertionError("rendered a case whose cells are known")


def test_known_cells_are_not_rendered_and_keep_their_place(written, default):
    cells, _, _ = written
    _, invariances, alpha, case = default
    out, _ = run_invariances([Refuses()], [case], invariances, known={("mitsuba", case.key): cells}, alpha=alpha)
    assert out == cells


def test_every_default_case_is_stored_and_current(mitsuba, default):
    """references/ holds the cells of every default case for this code; a change to what decides a cell
    (CHECK_SOURCES) needs `python -m harness references --invariances-only`. Only a Mitsuba other than the
    one they were rendered with may make them stale here (validate then renders them and says why)."""
    cases, invariances, alpha, _ = default
    _, misses = stored_cells([mitsuba], cases, invariances, alpha, IMAGE_BATCHES)
    misses = [m for m in misses if not m.endswith("stale (engine changed)")]
    assert misses == []
