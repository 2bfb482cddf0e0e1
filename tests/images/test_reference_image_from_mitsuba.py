"""A reference image that another renderer made: Mitsuba's mean image of N samples, given as
--reference-image, is accepted for our correct renderer over several seeds (its noise fits N, though
Mitsuba's estimators are not mcval's), and the same image 2 % too bright is rejected."""
import pytest

from harness.exr import write_layers
from harness.images.case_task import run_image_case
from harness.images.reference_image import ReferenceImage
from harness.images.suite import ImageCase

RES, BATCHES, SPP = 48, 4, 256


@pytest.fixture(scope="module", params=[("sphere_plane", "ao"), ("plane_point", "simple"), ("cornell", "normals")],
                ids=lambda p: ":".join(p))
def made(request, mitsuba, tmp_path_factory):
    """Mitsuba's image of the case, BATCHES x SPP samples, written as an EXR."""
    case = ImageCase(*request.param)
    image = mitsuba.render(str(mitsuba.scene_file(case.path)), case.integrator, SPP, BATCHES, 77,
                           {"res": str(RES)}).mean
    return case, image, tmp_path_factory.mktemp("ref")


def _run(mcval, case, image, folder, seed, name="ref.exr"):
    write_layers(folder / name, {"RGB": image})
    return run_image_case(case, mcval, ReferenceImage(folder / name, BATCHES * SPP), seed, 0.01, 0)


@pytest.mark.parametrize("seed", [1, 2])
def test_mitsubas_image_is_accepted(mcval, made, seed):
    case, image, folder = made
    result = _run(mcval, case, image, folder, seed)
    assert result.reference_problem is None, result.reference_problem
    assert result.passed, result.comparisons["image"].failed_checks


def test_mitsubas_image_two_percent_too_bright_is_rejected(mcval, made):
    case, image, folder = made
    if case.integrator == "normals":  # a signed image: 2 % of a normal is no radiance bias
        image = image + 0.02
    result = _run(mcval, case, 1.02 * image if case.integrator != "normals" else image, folder, 1, "biased.exr")
    assert not result.passed
