"""Engine files (docs/engines.md): every mistake in one is a line naming the file, the line and what was
expected, before any render."""
import pytest

from harness.engines.engine_file import EngineFileError, read_engine_file
from harness.engines.registry import make_engine

GOOD = '''name = "toy"
command = ["{here}/toy", "{scene}", "-o", "{output}"]
version = ["{here}/toy", "--version"]
[integrators]
ao = "occlusion"
'''


def _file(tmp_path, text: str, executable: bool = True):
    program = tmp_path / "toy"
    program.write_text("#!/bin/sh\necho toy 1.2\n")
    program.chmod(0o755 if executable else 0o644)
    path = tmp_path / "toy.toml"
    path.write_text(text)
    return path


def _error(tmp_path, text: str, executable: bool = True) -> str:
    with pytest.raises(EngineFileError) as e:
        read_engine_file(_file(tmp_path, text, executable))
    return str(e.value)


def test_a_good_file_reads_with_its_integrator_table_and_version(tmp_path):
    engine = make_engine(str(_file(tmp_path, GOOD)))
    assert engine.name == "toy" and engine.integrators == ("ao",)
    assert engine.describe()["version"] == "toy 1.2"
    assert engine.file.integrators == {"ao": "occlusion"} and engine.file.jobs == 1


def test_an_unknown_key_names_its_line(tmp_path):
    message = _error(tmp_path, GOOD.replace('version =', 'verison ='))
    assert message.endswith(":3: unknown key 'verison' (an engine file has name, command, version, scene_format, "
                            "jobs, timeout, integrators, other_estimators)")


@pytest.mark.parametrize("placeholder", ["scene", "output"])
def test_a_command_without_scene_or_output_is_refused(tmp_path, placeholder):
    message = _error(tmp_path, GOOD.replace("{" + placeholder + "}", "x"))
    assert f":2: command has no {{{placeholder}}}" in message


def test_an_unknown_placeholder_is_refused(tmp_path):
    assert ":2: unknown placeholder {samples}" in _error(tmp_path, GOOD.replace('"-o"', '"{samples}"'))


def test_a_missing_program_is_refused(tmp_path):
    assert "does not exist" in _error(tmp_path, GOOD.replace("{here}/toy\", \"{scene}", "{here}/nope\", \"{scene}"))
    assert "is not a program on PATH" in _error(tmp_path, GOOD.replace('"{here}/toy", "{scene}"',
                                                                          '"no-such-renderer", "{scene}"'))


def test_a_program_that_is_a_folder_is_called_a_folder(tmp_path):
    (tmp_path / "renderer").mkdir()
    message = _error(tmp_path, GOOD.replace("{here}/toy\", \"{scene}", "{here}/renderer\", \"{scene}"))
    assert message.endswith(f"{tmp_path / 'renderer'} is a folder, not a program"), message


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "0", "-5", "true", '"60"'])
def test_a_timeout_that_would_not_end_a_hung_render_is_refused(tmp_path, value):
    message = _error(tmp_path, GOOD.replace("[integrators]", f"timeout = {value}\n[integrators]"))
    assert ":4: timeout must be a finite positive number of seconds" in message, message


def test_a_program_that_is_not_executable_is_refused(tmp_path):
    assert "is not executable (chmod +x)" in _error(tmp_path, GOOD, executable=False)


def test_an_integrator_mcval_does_not_have_is_refused(tmp_path):
    message = _error(tmp_path, GOOD + 'bdpt = "bdpt"\n')
    assert ":6: integrators: 'bdpt' is not an integrator of mcval" in message


def test_other_estimators_says_which_integrators_are_judged_by_their_mean_only(tmp_path):
    plain = make_engine(str(_file(tmp_path, GOOD)))
    assert plain.file.other_estimators == frozenset() and plain.draws_integrator_estimator("ao")
    engine = make_engine(str(_file(tmp_path, 'other_estimators = ["ao"]\n' + GOOD)))
    assert engine.file.other_estimators == {"ao"} and not engine.draws_integrator_estimator("ao")


@pytest.mark.parametrize("line, expected", [
    ('other_estimators = "ao"\n', ":1: other_estimators must be a list of mcval's integrators"),
    ('other_estimators = ["simple"]\n', ":1: other_estimators: 'simple' is not in [integrators] (this renderer "
                                        "maps ao)"),
])
def test_other_estimators_must_list_mapped_integrators(tmp_path, line, expected):
    assert expected in _error(tmp_path, line + GOOD)


def test_a_top_level_key_written_below_the_integrator_table_is_said_to_belong_above_it(tmp_path):
    message = _error(tmp_path, GOOD + 'other_estimators = ["ao"]\n')
    assert message.endswith(":6: other_estimators is read as a line of [integrators]: write it above that table "
                            "(TOML gives every key after a [table] line to the table)"), message


def test_bad_toml_and_missing_keys_are_refused(tmp_path):
    assert ":2: not valid TOML" in _error(tmp_path, 'name = "toy"\ncommand = [\n')
    assert ":1: missing 'integrators'" in _error(tmp_path, GOOD.split("[integrators]")[0])
    assert "jobs must be a whole number" in _error(tmp_path, "jobs = 0\n" + GOOD)


@pytest.mark.parametrize("word", ["{output", "out}", "{output}}x"])
def test_an_unbalanced_placeholder_names_its_line_and_the_word(tmp_path, word):
    message = _error(tmp_path, GOOD.replace('"-o", "{output}"', f'"-o", "{word}", "{{output}}"'))
    assert f"toy.toml:2: command: {word!r} is not a word with placeholders" in message, message
    assert "a literal brace is written {{ or }}" in message


@pytest.mark.parametrize("content, line", [(b"name = 'toy'\n\x89PNG\r\n\x1a\n\x00\x00", 2),
                                          (b"\x7fELF\x02\x01\x01\x00\x00\x00", 1)])
def test_a_binary_file_is_not_a_toml_text_file(tmp_path, content, line):
    path = _file(tmp_path, GOOD)
    path.write_bytes(content)
    with pytest.raises(EngineFileError) as e:
        read_engine_file(path)
    assert str(e.value).startswith(f"{path}:{line}: not a TOML text file"), e.value
