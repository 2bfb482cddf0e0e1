"""A single reference image (--reference-image): our ao against an image our renderer made with N samples
passes and the image's noise fits N; the same image 3 % too bright fails; an image whose stated count is 16
times too small is reported as not fitting and does not pass, unless the noise model is `measured`; an image
of the wrong size, or with a NaN, fails the case with one line."""
import json

import numpy as np
import pytest

from harness.exr import write_layers
from harness.images.case_task import run_image_case
from harness.images.reference_image import ReferenceImage
from harness.images.suite import ImageCase

RES, K, SPP = 32, 8, 128
CASE = ImageCase("sphere_plane", "ao")


@pytest.fixture(scope="module")
def made(mcval):
    """Our ao of sphere_plane at RES, K batches of SPP samples: the mean image of K * SPP samples."""
    return mcval.render(str(CASE.path), "ao", SPP, K, 12345, {"res": str(RES)}).mean


def _image(tmp_path, pixels, name="ref.exr"):
    path = tmp_path / name
    write_layers(path, {"RGB": pixels})
    return path


def _run(mcval, path, spp, noise="stated", seed=3):
    return run_image_case(CASE, mcval, ReferenceImage(path, spp, noise), seed, 0.01, 0)


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_an_image_of_the_stated_count_passes(mcval, made, tmp_path, seed):
    result = _run(mcval, _image(tmp_path, made), K * SPP, seed=seed)
    assert result.error is None and result.reference_fit.fits, result.reference_fit.summary
    assert result.passed, result.comparisons["image"].failed_checks
    assert json.loads(json.dumps(result.to_json()))["reference_fit"]["fits"] is True


def test_a_biased_image_fails(mcval, made, tmp_path):
    result = _run(mcval, _image(tmp_path, 1.03 * made), K * SPP)
    assert result.reference_problem is None
    assert not result.passed and result.comparisons["image"].failed_checks


def test_a_stated_count_far_too_small_is_reported_and_does_not_pass(mcval, made, tmp_path):
    result = _run(mcval, _image(tmp_path, made), K * SPP // 16)
    assert not result.reference_fit.fits
    assert "does not fit its stated 64 spp" in result.reference_problem
    assert not result.passed
    measured = _run(mcval, _image(tmp_path, made), K * SPP // 16, noise="measured")
    assert measured.reference_problem is None and measured.passed


def test_an_image_of_another_size_fails_with_both_sizes(mcval, made, tmp_path):
    result = _run(mcval, _image(tmp_path, made[:, :-4]), K * SPP)
    assert not result.passed and "28x32 pixels, the render 28x28" in result.error


def test_an_image_with_a_nan_fails(mcval, made, tmp_path):
    bad = made.copy()
    bad[3, 4, 1] = np.nan
    result = _run(mcval, _image(tmp_path, bad), K * SPP)
    assert not result.passed and "NaN or infinite" in result.error


def test_the_case_is_the_one_whose_integrator_the_file_names(tmp_path):
    from argparse import Namespace

    from harness.commands.reference_image_options import chosen_image_case

    scene = tmp_path / "s.xml"
    scene.write_text('<scene version="3.0.0"><integrator type="ao"/></scene>')
    cases = [ImageCase("s", name, "user", tmp_path) for name in ("normals", "ao")]
    args = Namespace(reference_image=tmp_path / "ref.exr")
    assert [c.key for c in chosen_image_case(args, cases)] == ["s:ao"]
    scene.write_text('<scene version="3.0.0"><integrator type="path"/></scene>')
    with pytest.raises(ValueError, match="choose its case with --only"):
        chosen_image_case(args, cases)
    assert chosen_image_case(Namespace(reference_image=None), cases) == cases
