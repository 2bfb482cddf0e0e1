"""The fuzz driver and its oracle: deterministic variants, every bad outcome recognised, a clean corpus."""
from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

from tests.helpers.render_wrappers import REAL_RENDER, write_wrapper

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fuzz_scenes  # noqa: E402
import mutate_lights  # noqa: E402
import replay  # noqa: E402
from light_seeds import DELTA_SCENE  # noqa: E402
from outcome import judge  # noqa: E402

from tests.helpers.registered_integrators import PRODUCT  # noqa: E402

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "plane_point.xml"


def _case(tmp_path: Path) -> Path:
    folder = tmp_path / "case"
    folder.mkdir(parents=True)
    shutil.copy(SCENE, folder / "scene.xml")
    return folder / "scene.xml"


def test_variants_are_the_same_for_the_same_seed(tmp_path):
    seeds = fuzz_scenes.load_seeds()
    for index in (0, 7, 123):
        a = fuzz_scenes.make_variant(index, 5, seeds, tmp_path / "a")
        b = fuzz_scenes.make_variant(index, 5, seeds, tmp_path / "b")
        assert (a.seed, a.integrator, a.mutation) == (b.seed, b.integrator, b.mutation)
        files = sorted(p.relative_to(a.folder) for p in a.folder.rglob("*") if p.is_file() and not p.is_symlink())
        for f in files:
            assert (a.folder / f).read_bytes() == (b.folder / f).read_bytes(), f


def test_the_variants_render_under_every_integrator_and_damage_the_lights(tmp_path):
    seeds = fuzz_scenes.load_seeds()
    variants = [fuzz_scenes.make_variant(i, 5, seeds, tmp_path) for i in range(300)]
    assert {v.integrator for v in variants} == set(PRODUCT)
    assert any(v.integrator == "direct" and "light" in v.mutation for v in variants)


@pytest.mark.parametrize("name, mutation", [(name, op) for name, op, _ in mutate_lights.MUTATIONS])
def test_each_light_mutation_changes_a_scene_that_has_what_it_damages(name, mutation):
    import random
    changed = {mutation(random.Random(k), DELTA_SCENE) for k in range(20)}
    assert None not in changed and DELTA_SCENE not in changed, name
    assert mutation(random.Random(7), DELTA_SCENE) == mutation(random.Random(7), DELTA_SCENE)


@pytest.mark.parametrize("behaviour, outcome", [("segfault", "signal"), ("hang", "hang"), ("no_image", "bad-image"),
                                                ("nan_image", "bad-image"), ("negative_image", "bad-image"),
                                                ("leftover", "leftover")])
def test_the_oracle_recognises_each_bad_outcome(tmp_path, behaviour, outcome):
    render = write_wrapper(tmp_path, behaviour, "ao")
    got, detail = judge(render, _case(tmp_path), "ao", timeout=3)
    assert got == outcome, detail


def test_negative_normals_are_an_image_and_scene_errors_are_errors(tmp_path):
    assert judge(write_wrapper(tmp_path, "negative_image", "normals"), _case(tmp_path), "normals", 60)[0] == "image"
    scene = _case(tmp_path / "x")
    scene.write_text(scene.read_text().replace('value="5, 5, 5"', 'value="nan"'))
    outcome, detail = judge(REAL_RENDER, scene, "simple", 60)
    assert outcome == "error" and "expected a finite number" in detail


def test_the_corpus_replays_cleanly():
    """Every reproducer of tests/fuzz/corpus gives the image or the error it expects (the sanitizer run
    of `make sanitize` replays the same corpus)."""
    failures = [p for case in replay.corpus_cases() if (p := replay.replay(REAL_RENDER, *case, timeout=120))]
    assert not failures, "\n".join(failures)


def test_a_short_campaign_finds_nothing(tmp_path):
    assert fuzz_scenes.main(["--runs", "60", "--seed", "3", "--render", str(REAL_RENDER), "--work",
                             str(tmp_path / "work"), "--save", str(tmp_path / "crashes"), "--jobs", "2"]) == 0
    assert not (tmp_path / "crashes").exists()
