"""Scene files sent by content: a worker's copy holds the same bytes under the same relative paths."""

from harness.distributed.bundle import bundle_files
from harness.images.case_task import scene_bundle
from harness.images.references import reference_path
from harness.images.suite import ImageCase


def test_a_scene_bundle_holds_the_scene_its_meshes_and_its_references(tmp_path, mitsuba):
    case = ImageCase("highpoly", "ao")
    bundle = scene_bundle(case, [mitsuba])
    names = {rel for rel, _ in bundle.files}
    assert {"scenes/highpoly.xml", "scenes/meshes/highpoly.ply", "references/mitsuba/highpoly/ao.exr",
            "references/mitsuba/highpoly/ao.json"} <= names
    root = bundle.materialize(tmp_path)
    copy = ImageCase("highpoly", "ao", root=root)
    assert copy == case and copy.path.read_bytes() == case.path.read_bytes()
    assert reference_path(copy, mitsuba).read_bytes() == reference_path(case, mitsuba).read_bytes()
    assert bundle.materialize(tmp_path) == root  # written once


def test_the_digest_follows_every_byte(tmp_path):
    (tmp_path / "meshes").mkdir()
    scene, mesh = tmp_path / "s.xml", tmp_path / "meshes" / "m.ply"
    scene.write_text('<scene><shape type="ply"><string name="filename" value="meshes/m.ply"/></shape></scene>')
    mesh.write_bytes(b"ply\n0")
    first = bundle_files(tmp_path, [scene])
    assert {rel for rel, _ in first.files} == {"s.xml", "meshes/m.ply"}
    mesh.write_bytes(b"ply\n1")
    assert bundle_files(tmp_path, [scene]).digest != first.digest
    mesh.unlink()  # a missing mesh is left out: the worker finds it missing, as this machine would
    assert {rel for rel, _ in bundle_files(tmp_path, [scene]).files} == {"s.xml"}
