"""toolpath/engines/meshdata.py: polygons into triangles (fans) and the polygon each came from, written
out by hand for small meshes: a triangle stays as it is, a quad and a pentagon fan from corner 0,
a degenerate polygon (fewer than three corners) gives nothing."""
import numpy as np

from kezuri.toolpath.engines import meshdata


def test_fans_of_mixed_polygons():
    faces, owner = meshdata.triangulated([[0, 1, 2], np.array([2, 1, 3, 4]), [5, 6], [7, 8, 9, 10, 11]])
    assert faces.tolist() == [[0, 1, 2], [2, 1, 3], [2, 3, 4], [7, 8, 9], [7, 9, 10], [7, 10, 11]]
    assert owner.tolist() == [0, 1, 1, 3, 3, 3]
    assert faces.dtype == np.int64 and owner.dtype == np.int64


def test_nothing_to_triangulate():
    for polygons in ([], [[0, 1]], [[3]]):
        faces, owner = meshdata.triangulated(polygons)
        assert faces.shape == (0, 3) and owner.shape == (0,)
