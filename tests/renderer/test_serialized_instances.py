"""<shape type="serialized"> and shapegroup/instance: a scene of our own (serialized files written by
tests/helpers/serialized_files.py, a shapegroup placed by three instances, one mirroring) renders under
`normals` in our engine as in Mitsuba 3, and a planted difference on either side is caught."""
import numpy as np
import pytest

from harness.comparison.compare import compare_batches
from tests.helpers.serialized_files import pyramid, uv_sphere, write_serialized

K, SPP = 6, 16

INSTANCES = {
    "moved": '<translate value="-2.2, 0, 0"/>',
    "turned": '<rotate y="1" angle="70"/><scale value="1.2"/><translate value="2.2, 0, 0"/>',
    "mirrored": '<scale value="-1, 1, 1"/><rotate x="1" angle="20"/><translate value="0, 1.8, -1"/>',
}


def _scene(folder, instances=INSTANCES, shape_index=1, flip="true") -> str:
    """A shapegroup (a serialized sphere, an exact sphere and a cube) under three instances; at the top level,
    a pyramid (shape 1 of a version-3 file: the other table) flat-shaded, and the serialized sphere flipped."""
    write_serialized(folder / "meshes.serialized", [uv_sphere(), pyramid()], version=4)
    write_serialized(folder / "meshes_v3.serialized", [uv_sphere(), pyramid()], version=3)
    placed = "\n".join(f'<shape type="instance"><ref id="group"/><transform name="to_world">{t}</transform></shape>'
                       for t in instances.values())
    path = folder / "scene.xml"
    path.write_text(f"""<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 2.5, 7" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="{SPP}"/></sampler>
        <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="48"/>
            <rfilter type="box"/></film>
    </sensor>
    <shape type="shapegroup" id="group">
        <shape type="serialized"><string name="filename" value="meshes.serialized"/>
            <transform name="to_world"><scale value="0.7"/></transform></shape>
        <shape type="sphere"><point name="center" value="0.9, 0.6, 0"/><float name="radius" value="0.3"/></shape>
        <shape type="cube"><transform name="to_world"><scale value="0.25, 0.5, 0.25"/>
            <translate value="-0.9, 0, 0.3"/></transform></shape>
    </shape>
    {placed}
    <shape type="serialized"><string name="filename" value="meshes_v3.serialized"/>
        <integer name="shape_index" value="{shape_index}"/><boolean name="face_normals" value="true"/>
        <transform name="to_world"><scale value="0.8"/><translate value="0, -0.2, -3"/></transform></shape>
    <shape type="serialized"><string name="filename" value="meshes.serialized"/>
        <boolean name="flip_normals" value="{flip}"/>
        <transform name="to_world"><scale value="0.5"/><translate value="-1, -1.3, 1.5"/></transform></shape>
</scene>""")
    return str(path)


def _render(engine, scene, seed):
    return engine.render(scene, "normals", SPP, K, seed).batches


def test_mcval_and_mitsuba_agree(mcval, mitsuba, tmp_path):
    scene = _scene(tmp_path)
    test, reference = _render(mcval, scene, 1), _render(mitsuba, scene, 101)
    assert (np.abs(test).sum(axis=-1) > 0).mean() > 0.2  # the shapes fill a good part of the view
    assert compare_batches(test, reference, signed=True).passed


PLANTED = {
    "an instance turned": {"instances": {**INSTANCES, "turned": INSTANCES["turned"].replace("70", "50")}},
    "the file's other shape": {"shape_index": 0},
    "flip_normals left out": {"flip": "false"},
}


@pytest.mark.parametrize("planted", PLANTED)
def test_a_planted_difference_is_caught(mcval, mitsuba, tmp_path, planted):
    reference = _render(mitsuba, _scene(tmp_path), 101)
    (tmp_path / "wrong").mkdir()
    wrong = _scene(tmp_path / "wrong", **PLANTED[planted])
    assert not compare_batches(_render(mcval, wrong, 1), reference, signed=True).passed
