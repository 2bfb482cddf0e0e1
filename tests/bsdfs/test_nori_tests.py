"""`bsdfs --nori-test`: Nori's BSDF test files, read as they are and judged as Nori judges them. Our microfacet and
the example library pass Nori's ttest at Nori's stated references (the course's pa5 values) and its chi2test;
a microfacet with alpha where alpha^2 belongs fails the chi2test, a reference off by 2 % fails the ttest; a file
that cannot be read or mapped is refused in one line naming its place."""
import json
from pathlib import Path

import pytest

from harness.cli import main
from harness.commands.nori_test_section import library_values
from harness.engines.nori.test_files import read_nori_test
from tests.helpers.warp_libraries import build_warp_library

HERE = Path(__file__).resolve().parent
EXAMPLE = HERE.parents[1] / "examples" / "bsdfs" / "nori_microfacet.c"

#: Nori pa5's ttest of its microfacet: the angles, references and BSDF its file states.
NORI_ANGLES = "0, 45, 60, 80, 85"
NORI_REFERENCES = [0.207067, 0.215733, 0.247884, 0.430936, 0.519016]
MICROFACET = """<bsdf type="microfacet">
    <float name="alpha" value="{alpha}"/>
    <float name="intIOR" value="{int_ior}"/>
    <float name="extIOR" value="{ext_ior}"/>
    <color name="kd" value="{kd}"/>
</bsdf>"""


def _ttest(tmp_path: Path, references, name="ttest.xml") -> Path:
    path = tmp_path / name
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<test type="ttest">
<string name="angles" value="{NORI_ANGLES}"/>
<string name="references" value="{', '.join(map(str, references))}"/>
{MICROFACET.format(alpha=0.1, int_ior=1.5, ext_ior=1.000277, kd="0.1, 0.2, 0.15")}
</test>""")
    return path


def _chi2test(tmp_path: Path, bsdfs: str) -> Path:
    path = tmp_path / "chi2test.xml"
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<test type="chi2test">
<integer name="sampleCount" value="200000"/>
<integer name="testCount" value="2"/>
{bsdfs}
</test>""")
    return path


def _run(tmp_path: Path, *args: str) -> tuple[int, dict]:
    out = tmp_path / "r"
    code = main(["bsdfs", "--angles", "30", "--samples", "50000", "--out", str(out), *args])
    return code, json.loads((out / "latest" / "results.json").read_text())


def _nori_verdicts(results: dict) -> list[bool]:
    return [t["pass"] for block in results["nori_tests"] for t in block["tests"]]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_our_microfacet_passes_noris_ttest_at_noris_references(tmp_path, seed):
    code, results = _run(tmp_path, "--nori-test", str(_ttest(tmp_path, NORI_REFERENCES)), "--seed", str(seed))
    assert code == 0 and _nori_verdicts(results) == [True] * 5, results["nori_tests"]
    assert [row["bsdf"] for row in results["bsdfs"]] == ["microfacet alpha=0.1 kd=0.175124 ks=0.8 int_ior=1.5 "
                                                         "ext_ior=1.00028"]  # kd's luminance, ks = 1 - max(kd)


def test_a_reference_two_percent_off_fails_noris_ttest(tmp_path):
    code, results = _run(tmp_path, "--nori-test", str(_ttest(tmp_path, [r * 1.02 for r in NORI_REFERENCES])))
    assert code == 1 and not any(_nori_verdicts(results))
    assert all(row["pass"] for row in results["bsdfs"])  # mcval's own checks of the BSDF hold


def test_our_microfacet_passes_noris_chi2test(tmp_path):
    bsdfs = "\n".join(MICROFACET.format(alpha=a, int_ior=i, ext_ior=e, kd=kd) for a, i, e, kd in [
        (0.15, 1.33, 1.0, "0, 0, 0"), (0.4, 1.5, 1.01, "0.3, 0.1, 0.5"), (0.7, 1.7, 1.2, "0.2, 0.4, 0.3")])
    code, results = _run(tmp_path, "--nori-test", str(_chi2test(tmp_path, bsdfs)))
    assert code == 0 and _nori_verdicts(results) == [True] * 6, results["nori_tests"]
    assert len(results["bsdfs"]) == 3 and all(row["pass"] for row in results["bsdfs"])


def test_a_microfacet_with_alpha_for_alpha2_fails_noris_chi2test(tmp_path, microfacet_twins):
    bsdfs = '<bsdf type="alpha_for_alpha2"><float name="alpha" value="0.3"/></bsdf>'
    code, results = _run(tmp_path, "--nori-test", str(_chi2test(tmp_path, bsdfs)), "--bsdf-library",
                         str(microfacet_twins.path))
    assert code == 1 and _nori_verdicts(results) == [False, False]
    assert "chi^2" in results["nori_tests"][0]["tests"][0]["message"]


def test_the_example_library_passes_noris_ttest(tmp_path):
    library = build_warp_library(EXAMPLE, tmp_path)
    code, results = _run(tmp_path, "--nori-test", str(_ttest(tmp_path, NORI_REFERENCES)), "--bsdf-library",
                         str(library))
    assert code == 0 and _nori_verdicts(results) == [True] * 5, results["nori_tests"]


def test_a_coloured_kd_needs_a_ks_parameter(tmp_path):
    """A gray library without ks cannot carry Nori's coloured kd: refused, naming the element."""
    test = read_nori_test(_ttest(tmp_path, NORI_REFERENCES, "coloured.xml"))
    with pytest.raises(ValueError, match=r"coloured\.xml:5: <bsdf type=\"microfacet\">: kd \(0\.1, 0\.2, 0\.15\) is "
                                         "coloured"):
        library_values(test.bsdfs[0], ["alpha", "kd", "int_ior", "ext_ior"])


@pytest.mark.parametrize("text, message", [
    ('<test type="ttest"><string name="angles" value="0, 45"/><string name="references" value="0.2"/>'
     '<bsdf type="diffuse"/></test>', r"bad\.xml:1: <test type=\"ttest\">: expected one reference per angle and BSDF"),
    ('<test type="chi2test">\n<scene/></test>', r"bad\.xml:2: <scene>: expected <bsdf> or a property of the chi2test"),
    ('<test type="chi2test">\n<float name="level" value="0.1"/><bsdf type="diffuse"/></test>',
     r"bad\.xml:2: <float name=\"level\" value=\"0\.1\">: chi2test has no property 'level'"),
    ('<test type="warptest"/>', r"expected <test type=\"\.\.\.\"> of type chi2test or ttest"),
    ('<test type="chi2test">\n<bsdf type="microfacet">\n<color name="kd" value="0.5"/></bsdf></test>',
     r"bad\.xml:3: <color name=\"kd\" value=\"0\.5\">: expected three finite numbers"),
    ('<test type="chi2test"><bsdf type="diffuse">', r"bad\.xml:1: not valid XML"),
])
def test_a_file_that_cannot_be_read_is_refused_in_one_line(tmp_path, text, message):
    path = tmp_path / "bad.xml"
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        read_nori_test(path)


def test_the_command_refuses_a_missing_file_before_any_run(tmp_path, capsys):
    assert main(["bsdfs", "--nori-test", str(tmp_path / "none.xml"), "--out", str(tmp_path / "r")]) == 2
    assert "none.xml: no such file" in capsys.readouterr().err
