"""Meshes written for Nori as OBJ files (harness/engines/nori/baked_obj.py, obj_mesh.py, ply_mesh.py): an OBJ
Nori shades as Mitsuba does is named as it is, every other mesh is baked into world space with the normals
Mitsuba shades it with, checked against Mitsuba's own positions and normals."""
import resource
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness.images.suite import SCENES_DIR
from tests.engines.nori.test_to_nori import props, refused, write

PLY = """ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 1
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
4 0 1 2 3
"""


def test_a_ply_mesh_becomes_a_world_space_obj_with_mitsubas_normals(tmp_path):
    (tmp_path / "quad.ply").write_text(PLY)
    body = '<shape type="ply"><string name="filename" value="quad.ply"/><transform name="to_world"><rotate ' \
           'x="1" angle="90"/><translate value="0, 0, 5"/></transform></shape>'
    root, _, _, files = write(tmp_path, body)
    (mesh,) = root.findall("mesh")
    assert props(mesh)["filename"] == "ply_0.obj" and mesh.find("transform") is None
    lines = files["ply_0.obj"].splitlines()
    v = [[float(x) for x in line.split()[1:]] for line in lines if line.startswith("v ")]
    assert np.allclose(v, [[0, 0, 5], [1, 0, 5], [1, 0, 6], [0, 0, 6]], atol=1e-12)
    vn = [[float(x) for x in line.split()[1:]] for line in lines if line.startswith("vn ")]
    assert np.allclose(vn, [[0, -1, 0]] * 4, atol=1e-12)  # +z turned by 90 degrees about x
    assert [line for line in lines if line.startswith("f ")] == ["f 1//1 2//2 3//3", "f 1//1 3//3 4//4"]
    flat, _, _, files = write(tmp_path, body.replace("</shape>", '<boolean name="face_normals" value="true"/>'
                                                                    "</shape>"))
    assert "vn " not in files["ply_0.obj"] and "f 1 2 3" in files["ply_0.obj"]
    (tmp_path / "broken.ply").write_text("ply\nformat ascii 1.0\nend_header\n")
    refused(tmp_path, "cannot be written as OBJ for Nori", body=body.replace("quad.ply", "broken.ply"))


def test_computed_normals_weigh_each_triangle_by_its_angle():
    from harness.engines.nori.baked_obj import _vertex_normals
    # Vertex 0 is shared by a triangle in z = 0 with 90 degrees there and one in x = 0 with about 5.7 degrees
    # there but ten times the area: angle weighting leans to the first (+z), area weighting to the second (-x).
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 10], [0, 1, 10.0]])
    n = _vertex_normals(p, np.array([[0, 1, 2], [0, 3, 4]]))[0]
    angle = np.arccos(np.dot(p[3], p[4]) / (np.linalg.norm(p[3]) * np.linalg.norm(p[4])))
    expected = np.pi / 2 * np.array([0, 0, 1.0]) + angle * np.array([-1.0, 0, 0])
    assert n[2] > -n[0] > 0
    assert n == pytest.approx(expected / np.linalg.norm(expected))


def test_an_obj_mesh_with_normals_is_named_and_one_without_is_baked_with_mitsubas(tmp_path):
    (tmp_path / "smooth.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n")
    (tmp_path / "bare.obj").write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3 4\n")
    to_world = '<transform name="to_world"><translate x="2"/></transform>'
    root, _, _, files = write(tmp_path, f'<shape type="obj"><string name="filename" value="smooth.obj"/>{to_world}'
                                        '</shape>')
    (mesh,) = root.findall("mesh")
    assert props(mesh)["filename"] == str(tmp_path / "smooth.obj") and files == {}
    assert mesh.find("transform/translate").attrib == {"value": "2, 0, 0"}
    root, _, _, files = write(tmp_path, f'<shape type="obj"><string name="filename" value="bare.obj"/>{to_world}'
                                        '</shape>')
    (mesh,) = root.findall("mesh")
    assert props(mesh)["filename"] == "obj_0.obj" and mesh.find("transform") is None
    lines = files["obj_0.obj"].splitlines()
    assert [line for line in lines if line.startswith("v ")][0] == "v 2 0 0"
    assert len([line for line in lines if line.startswith("vn ")]) == 4  # a fan of two over four corners
    assert [line for line in lines if line.startswith("f ")] == ["f 1//1 2//2 3//3", "f 1//1 3//3 4//4"]
    flat, _, _, files = write(tmp_path, '<shape type="obj"><string name="filename" value="bare.obj"/><boolean '
                                        'name="face_normals" value="true"/></shape>')
    assert props(flat.find("mesh"))["filename"] == str(tmp_path / "bare.obj") and files == {}
    # face_normals drops a file's own normals: baked without any.
    root, _, _, files = write(tmp_path, '<shape type="obj"><string name="filename" value="smooth.obj"/><boolean '
                                        'name="face_normals" value="true"/></shape>')
    assert "vn " not in files["obj_0.obj"]
    refused(tmp_path, "cannot be written as OBJ", body='<shape type="obj"><string name="filename" '
                                                       'value="missing.obj"/></shape>')


STEPS = '<scale value="2, 1, 0.5"/><rotate x="1" y="1" angle="30"/><matrix value="1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1"/>' \
        '<lookat origin="1, 2, 3" target="0, 1, 0" up="0, 0, 1"/><translate x="-1"/>'


@pytest.mark.mitsuba
def test_baked_positions_are_where_mitsuba_puts_them():
    import mitsuba as mi
    from harness.engines.nori.baked_obj import transform_matrix
    mi.set_variant("scalar_rgb")
    scene = mi.load_string(f'<scene version="3.0.0"><shape type="obj" id="s"><string name="filename" '
                           f'value="{SCENES_DIR.parent / "tests/engines/nori/tri.obj"}"/><transform name="to_world">'
                           f'{STEPS}</transform></shape></scene>')
    theirs = np.array(mi.traverse(scene)["s.vertex_positions"]).reshape(-1, 3)
    m = transform_matrix(ET.fromstring(f"<transform>{STEPS}</transform>"))
    corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    assert np.allclose(corners @ m[:3, :3].T + m[:3, 3], theirs, atol=1e-5)
    swapped = transform_matrix(ET.fromstring(f"<transform>{STEPS.replace('30', '-30')}</transform>"))
    assert not np.allclose(corners @ swapped[:3, :3].T + swapped[:3, 3], theirs, atol=1e-3)


@pytest.mark.mitsuba
@pytest.mark.parametrize("kind", ["obj", "ply"])
def test_baked_normals_are_mitsubas(tmp_path, kind):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    # A bent strip of four triangles, unevenly scaled: the normals are computed in world space, angle-weighted.
    p = [(0, 0, 0), (1, 0, 0.3), (2, 0, 0), (0, 1, 0.5), (1, 1, 0), (2, 1, 0.8)]
    faces = [(0, 1, 4), (0, 4, 3), (1, 2, 5), (1, 5, 4)]
    if kind == "obj":
        (tmp_path / "strip.obj").write_text("".join(f"v {x} {y} {z}\n" for x, y, z in p) +
                                            "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces))
    else:
        (tmp_path / "strip.ply").write_text(PLY.replace("element vertex 4", "element vertex 6").replace(
            "element face 1", "element face 4").split("end_header\n")[0] + "end_header\n" +
            "".join(f"{x} {y} {z}\n" for x, y, z in p) + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces))
    to_world = '<transform name="to_world"><scale value="1, 3, 0.5"/><rotate z="1" angle="20"/></transform>'
    shape = f'<shape type="{kind}" id="s"><string name="filename" value="{tmp_path / f"strip.{kind}"}"/>' \
            f'{to_world}</shape>'
    _, _, _, files = write(tmp_path, shape)
    lines = files[f"{kind}_0.obj"].splitlines()
    mcval_p = np.array([[float(x) for x in line.split()[1:]] for line in lines if line.startswith("v ")])
    mcval_n = np.array([[float(x) for x in line.split()[1:]] for line in lines if line.startswith("vn ")])
    params = mi.traverse(mi.load_string(f'<scene version="3.0.0">{shape}</scene>'))
    theirs_p = np.array(params["s.vertex_positions"]).reshape(-1, 3)
    theirs_n = np.array(params["s.vertex_normals"]).reshape(-1, 3)
    order = [int(np.argmin(np.linalg.norm(mcval_p - q, axis=1))) for q in theirs_p]
    assert np.allclose(mcval_p[order], theirs_p, atol=1e-5)
    assert np.allclose(mcval_n[order], theirs_n, atol=1e-5)
    wrong = mcval_n.copy()
    wrong[1] = [0, 0, 1]  # a wrong normal at one vertex is seen
    assert not np.allclose(wrong[order], theirs_n, atol=1e-5)


# Each reader of a named mesh file, given a device and a pipe: run in a child with a time and memory limit, as
# a reader that reads them reads without end.
ENDLESS_READS = """
import os, sys, tempfile
from pathlib import Path
from harness.engines.nori.obj_mesh import read_obj
from harness.engines.nori.ply_mesh import PlyError, read_ply
from harness.engines.nori.reader import obj_has_normals
from harness.images.references import scene_hash
fifo = Path(tempfile.mkdtemp()) / "fifo"
os.mkfifo(fifo)
for path in ("/dev/zero", fifo):
    for read in (read_obj, read_ply):
        try:
            read(Path(path))
            sys.exit(f"{read.__name__} read {path}")
        except PlyError as e:
            assert "not a regular file" in str(e), e
    assert obj_has_normals(str(path), fifo) is None
    scene = fifo.with_name("scene.xml")
    scene.write_text(f'<scene><shape type="obj"><string name="filename" value="{path}"/></shape></scene>')
    scene_hash(scene)
print("ok")
"""


def test_a_device_or_a_pipe_named_as_a_mesh_is_refused_not_read():
    def limit_memory():
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    done = subprocess.run([sys.executable, "-c", ENDLESS_READS], capture_output=True, text=True, timeout=60,
                          preexec_fn=limit_memory)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr[-2000:]
