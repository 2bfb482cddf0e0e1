"""Each engine says how it renders mcval's integrators and whether it draws their estimators: the interface's
defaults, an engine file's [integrators] table, our renderer's registry and Mitsuba's table."""
from pathlib import Path

from harness.engines.base import Engine
from harness.engines.command import CommandEngine
from tests.helpers.registered_integrators import PRODUCT

ROOT = Path(__file__).resolve().parents[2]
CORNELL = ROOT / "scenes" / "cornell.xml"


class _Plain(Engine):
    name = "plain"

    def version(self) -> str:
        return "plain"


def test_an_engine_renders_every_integrator_by_its_name_and_claims_no_estimator():
    plain = _Plain()
    assert plain.integrator_mapping("ao") == "ao" and not plain.draws_same_estimator(CORNELL, "ao")
    plain.integrators = ("normals",)
    assert plain.integrator_mapping("ao") is None


def test_an_engine_file_maps_by_its_integrators_table(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text('name = "mine"\ncommand = ["true", "{scene}", "{output}"]\nscene_format = "nori"\n'
                    '[integrators]\nao = "ao_mine"\n')
    engine = CommandEngine.from_path(path)
    assert engine.integrators == ("ao",)
    assert engine.integrator_mapping("ao") == '<integrator type="ao_mine"> (nori scene)'
    assert engine.integrator_mapping("simple") is None
    assert not engine.draws_same_estimator(CORNELL, "ao")


def test_an_engine_file_takes_directs_strategy_from_the_scene_where_it_can_be_passed_on(tmp_path):
    def engine(scene_format: str, direct: str) -> CommandEngine:
        path = tmp_path / f"{scene_format}_{direct}.toml"
        path.write_text(f'name = "mine"\ncommand = ["true", "{{scene}}", "{{output}}"]\nscene_format = '
                        f'"{scene_format}"\n[integrators]\ndirect = "{direct}"\nao = "direct_mats"\n')
        return CommandEngine.from_path(path)

    assert engine("nori", "direct_mis").reads_integrator_parameters("direct")
    assert not engine("nori", "direct_mis").reads_integrator_parameters("ao")  # ao has no strategies to pass on
    assert not engine("nori", "my_direct").reads_integrator_parameters("direct")  # not one of Nori's three
    assert engine("mitsuba", "direct_mis").reads_integrator_parameters("direct")  # the file's values passed on
    assert not engine("mitsuba", "direct_mis").reads_integrator_parameters("normals")  # normals has none
    assert not engine("nori", "direct_mis").reads_integrator_parameters("simple")  # not in its table


def test_our_renderer_lists_its_registry(mcval):
    assert set(mcval.integrators) == set(PRODUCT)


def test_mitsuba_says_its_plugin_and_where_its_estimator_is_mcval(mitsuba, tmp_path):
    assert mitsuba.integrator_mapping("simple").startswith("direct(emitter_samples=1, bsdf_samples=0)")
    assert mitsuba.draws_same_estimator(CORNELL, "simple")
    two = tmp_path / "two_lights.xml"
    two.write_text('<scene version="3.0.0"><emitter type="point"/><emitter type="point"/></scene>\n')
    assert not mitsuba.draws_same_estimator(two, "simple")  # one emitter sample picks one of them
