"""Choosing cases with --only: an integrator the engine under test does not render is named as such, not as
an unknown scene."""
import pytest

from harness.images.suite import select_cases


@pytest.mark.parametrize("only", ["plane_point:normals", "normals"])
def test_an_integrator_the_engine_lacks_is_named(only):
    with pytest.raises(ValueError) as e:
        select_cases([only], integrators=("ao", "simple"))
    assert str(e.value) == f"--only {only}: the engine under test does not render normals (it renders ao, simple)"


def test_an_unknown_scene_is_still_unknown():
    with pytest.raises(ValueError, match="unknown scene or case nowhere:normals"):
        select_cases(["nowhere:normals"], integrators=("ao", "simple"))
    assert [c.key for c in select_cases(["plane_point:simple"], integrators=("ao", "simple"))] == ["plane_point:simple"]
