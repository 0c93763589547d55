"""The one mesh-file reader (toolpath/engines/meshfile.py): hand-written STL and OBJ files read as the
file says, in mm, and every bad file refused naming the option and the file as typed."""
import math
import re

import numpy as np
import pytest

from kezuri.toolpath.engines.meshfile import MeshFileError, read_mesh
from kezuri.toolpath.ir.errors import InputError

# a 10 x 20 x 30 mm box, corner at the origin, as 12 triangles written corner by corner (an STL repeats them)
BOX = [(0, 0, 0), (10, 0, 0), (10, 20, 0), (0, 20, 0), (0, 0, 30), (10, 0, 30), (10, 20, 30), (0, 20, 30)]
BOX_FACES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
             (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def stl(path, triangles):
    """An ASCII STL of the triangles, every number as written (so 'nan' and 1e300 stay)."""
    facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in tri)
                     + "endloop\nendfacet\n" for tri in triangles)
    path.write_text(f"solid t\n{facets}endsolid t\n")
    return str(path)


def box_triangles(scale=1.0):
    return [[tuple(scale * v for v in BOX[i]) for i in face] for face in BOX_FACES]


def test_an_stl_box_is_read_in_mm_with_its_corners_merged(tmp_path):
    vertices, faces = read_mesh(stl(tmp_path / "box.stl", box_triangles()))
    assert vertices.shape == (8, 3) and faces.shape == (12, 3) and faces.dtype == np.int64
    assert sorted(map(tuple, vertices.tolist())) == sorted(tuple(float(v) for v in p) for p in BOX)
    assert vertices.min(axis=0).tolist() == [0.0, 0.0, 0.0] and vertices.max(axis=0).tolist() == [10.0, 20.0, 30.0]
    # every triangle is one of the file's, as written (same corners, same order round it)
    written = {tuple(BOX[i] for i in face) for face in BOX_FACES}
    read = {tuple(tuple(vertices[i]) for i in face) for face in faces}
    rotations = {t[k:] + t[:k] for t in written for k in range(3)}
    assert read <= rotations and len(read) == 12


def test_an_obj_is_read_as_its_lines_say(tmp_path):
    path = tmp_path / "tri.obj"
    path.write_text("v 0 0 0\nv 40 0 0\nv 0 30 0\nv 0 0 -10\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n")
    vertices, faces = read_mesh(str(path), "--surface")
    assert vertices.tolist() == [[0, 0, 0], [40, 0, 0], [0, 30, 0], [0, 0, -10]]
    assert faces.tolist() == [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]


@pytest.mark.parametrize("make, words", [
    (lambda d: str(d / "missing.stl"), "no such file"),
    (lambda d: (d / "noise.stl").write_bytes(np.random.default_rng(7).bytes(3000)) and str(d / "noise.stl"),
     "(the mesh has no faces|not a readable mesh)"),
    (lambda d: (d / "empty.stl").write_text("solid e\nendsolid e\n") and str(d / "empty.stl"), "the mesh has no faces"),
    (lambda d: stl(d / "nan part.stl", [[(0, 0, 0), (10, 0, 0), (math.nan, 10, 0)]] + box_triangles()[1:]),
     r"the mesh has a non-finite vertex coordinate \(NaN or infinity\)"),
    (lambda d: stl(d / "big.stl", box_triangles(1e300)), r"the mesh reaches 3e\+301 mm from the origin \(more than"),
    (lambda d: stl(d / "metres.stl", box_triangles(1e12)), r"the mesh reaches 3e\+13 mm"),
])
def test_bad_files_are_refused_naming_the_option_and_the_file(tmp_path, make, words):
    path = make(tmp_path)
    with pytest.raises(MeshFileError, match=f"^--part {re.escape(path)}: {words}") as raised:
        read_mesh(path, "--part")
    assert isinstance(raised.value, InputError)
