"""The planning mesh (toolpath/engines/facets.py): a mesh whose faces were split into many coplanar ones
plans on the coarse mesh it came from.  Expected face counts, volumes and areas are closed forms
of the solids; closedness is checked edge by edge here, not by the module."""
import math

import numpy as np
import pytest
import trimesh
from manifold3d import Manifold
from pointsets import hausdorff

from kezuri.toolpath.engines import facets
from kezuri.toolpath.operations.turnmill import turnmill
from kezuri.toolpath.engines.meshdata import MeshInputError
from kezuri.toolpath.engines.meshrays import check_mesh, face_normals


def subdivided(v, f, times):
    for _ in range(times):
        v, f = trimesh.remesh.subdivide(v, f)
    return check_mesh(v, f)


def closed(faces: np.ndarray) -> bool:
    """Every directed edge used once and its reverse used once: closed, no T-junction, one winding."""
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    forward = {tuple(e) for e in directed.tolist()}
    return len(forward) == len(directed) and all((w, u) in forward for u, w in forward)


def volume_area(v, f):
    tri = v[f]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0
    return volume, face_normals(tri)[1].sum()


def box_mesh(a, b, c):
    m = Manifold.cube((a, b, c)).translate((-a / 2, -b / 2, -c / 2)).to_mesh64()
    return np.array(m.vert_properties[:, :3], float), np.array(m.tri_verts, np.int64)


def cylinder_mesh(r, h, sides):
    m = Manifold.cylinder(h, r, r, sides).to_mesh64()
    return np.array(m.vert_properties[:, :3], float), np.array(m.tri_verts, np.int64)


@pytest.mark.parametrize("times", [1, 2, 3])
def test_subdivided_box_merges_back_to_twelve_triangles(times):
    a, b, c = 30.0, 20.0, 12.5
    v, f = subdivided(*box_mesh(a, b, c), times)
    assert len(f) == 12 * 4 ** times
    planning = facets.planning_mesh(v, f)
    assert len(planning.faces) == 12 and planning.merged == 6
    assert len(planning.vertices) == 8
    assert closed(planning.faces)
    volume, area = volume_area(planning.vertices, planning.faces)
    assert volume == pytest.approx(a * b * c, rel=1e-9)
    assert area == pytest.approx(2 * (a * b + b * c + c * a), rel=1e-9)
    # every input face maps to a planning face in its own plane
    n_in = face_normals(v[f])[0]
    n_out = face_normals(planning.vertices[planning.faces])[0]
    assert np.allclose(n_out[planning.group], n_in, atol=1e-9)
    assert np.allclose(n_in[planning.source], n_out, atol=1e-9)


@pytest.mark.parametrize("sides", [6, 24, 64])
def test_subdivided_cylinder_merges_back(sides):
    r, h = 20.0, 35.0
    v0, f0 = cylinder_mesh(r, h, sides)
    assert len(f0) == 4 * sides - 4                       # 2 per side, a fan of sides - 2 per cap
    v, f = subdivided(v0, f0, 2)
    planning = facets.planning_mesh(v, f)
    assert len(planning.faces) == 4 * sides - 4
    assert closed(planning.faces)
    volume, area = volume_area(planning.vertices, planning.faces)
    polygon = sides / 2 * r * r * math.sin(2 * math.pi / sides)
    assert volume == pytest.approx(polygon * h, rel=1e-9)
    assert area == pytest.approx(2 * polygon + sides * 2 * r * math.sin(math.pi / sides) * h, rel=1e-9)


def test_meshes_without_split_faces_come_back_unchanged():
    for v, f in (box_mesh(10, 20, 30), cylinder_mesh(5, 8, 32), turnmill.sample_part()[:2]):
        v, f = check_mesh(v, f)
        planning = facets.planning_mesh(v, f)
        assert planning.merged == 0
        assert planning.vertices is v and planning.faces is f
        assert np.array_equal(planning.group, np.arange(len(f)))


def test_labels_keep_faces_apart():
    """Faces with different labels are never merged: the top of the box labelled in two halves
    stays split along the line between them, and the mesh stays closed."""
    a, b, c = 30.0, 20.0, 10.0
    v, f = subdivided(*box_mesh(a, b, c), 2)
    centroid = v[f].mean(axis=1)
    labels = np.where((centroid[:, 2] > c / 2 - 1e-9) & (centroid[:, 0] > 0), 1, 2).astype(np.int8)
    planning = facets.planning_mesh(v, f, labels)
    assert closed(planning.faces)
    assert np.array_equal(labels[planning.source][planning.group], labels)
    volume, area = volume_area(planning.vertices, planning.faces)
    assert volume == pytest.approx(a * b * c, rel=1e-9)
    assert area == pytest.approx(2 * (a * b + b * c + c * a), rel=1e-9)
    tri = planning.vertices[planning.faces]
    top = tri[:, :, 2].min(axis=1) > c / 2 - 1e-9
    assert np.all((tri[top, :, 0].min(axis=1) >= -1e-9) | (tri[top, :, 0].max(axis=1) <= 1e-9))
    assert len(planning.faces) < len(f)


def test_subdivided_sample_plans_the_same_program():
    """The sample split into 64x the faces (the same surface) gives the same program: the radial
    operations move for move to 1e-9 mm; the axial ones (whose few balls pushed clear off a
    pocket wall depend on how the floor is triangulated) within 0.05 mm of each other, point set
    to point set, with the point counts within 0.1 %.  The labels cover the same area per class."""
    v, f, stock = turnmill.sample_part()
    dv, df = subdivided(v, f, 3)
    plain, dense = turnmill.plan(v, f, stock), turnmill.plan(dv, df, stock)
    assert [op.name for op in plain.program.operations] == [op.name for op in dense.program.operations]
    for a, b in zip(plain.program.operations, dense.program.operations):
        if a.name.startswith("radial"):
            assert a.xyz.shape == b.xyz.shape and np.abs(a.xyz - b.xyz).max() < 1e-9
        else:
            assert abs(len(a.xyz) - len(b.xyz)) <= 0.001 * len(a.xyz)
            assert hausdorff(a.xyz, b.xyz) < 0.05
    assert len(dense.labels) == len(df)
    areas, dense_areas = face_normals(v[f])[1], face_normals(dv[df])[1]
    for label in (turnmill.NEITHER, turnmill.RADIAL, turnmill.AXIAL, turnmill.BOTH):
        assert dense_areas[dense.labels == label].sum() == pytest.approx(
            areas[plain.labels == label].sum(), rel=1e-9, abs=1e-9)
    for name in ("radial_faces", "axial_faces"):
        assert dense_areas[getattr(dense, name)].sum() == pytest.approx(
            areas[getattr(plain, name)].sum(), rel=1e-9)


def test_face_pass_gives_the_closed_form_volume_and_areas_of_a_box():
    """The compiled one-pass normals/areas/volume against the box's closed form."""
    from kezuri.toolpath.engines import facets_kernel
    a, b, c = 30.0, 20.0, 12.5
    v, f = subdivided(*box_mesh(a, b, c), 2)
    normals, areas, volume = facets_kernel.face_pass(v, f)
    assert volume == pytest.approx(a * b * c, rel=1e-12)
    assert areas.sum() == pytest.approx(2 * (a * b + b * c + c * a), rel=1e-12)
    # each unit normal is one of the six axis directions
    assert np.allclose(np.sort(np.abs(normals), axis=1), [0.0, 0.0, 1.0], atol=1e-12)
    inward = f[:, ::-1]
    assert facets_kernel.face_pass(v, inward)[2] == pytest.approx(-a * b * c, rel=1e-12)


def test_a_mesh_changed_in_place_after_its_check_is_checked_again():
    """check_mesh keeps nothing between calls: the caller's arrays changed in place after one check
    are checked afresh (flipped faces and a NaN vertex are refused)."""
    v, f = box_mesh(30.0, 20.0, 12.5)
    check_mesh(v, f)
    f[:] = f[:, ::-1]                        # every face flipped: the normals now point inward
    with pytest.raises(MeshInputError, match="inward"):
        check_mesh(v, f)
    f[:] = f[:, ::-1]
    v[0] = np.nan
    with pytest.raises(MeshInputError, match="NaN"):
        check_mesh(v, f)


def test_what_the_check_found_is_handed_on_not_remembered():
    """checked_mesh keeps what the mesh check found on the object it returns: each directed edge's
    reverse edge row and the face normals and areas (here checked edge by edge and against the
    box's closed forms); the planning mesh given them plans the same as it does finding them
    itself, and a second check of another mesh leaves the first object as it was."""
    pytest.importorskip("numba")
    from kezuri.toolpath.engines.meshrays import checked_mesh

    a, b, c = 30.0, 20.0, 12.5
    v, f = subdivided(*box_mesh(a, b, c), 1)
    mesh = checked_mesh(v, f)
    if mesh.reverse is None:
        pytest.skip("the numpy path keeps no edges (KEZURI_NO_NUMBA=1)")
    directed = mesh.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    assert np.array_equal(directed[mesh.reverse], directed[:, ::-1])          # closed: every edge has its twin
    normals, areas = mesh.normals
    assert areas.sum() == pytest.approx(2 * (a * b + b * c + c * a), rel=1e-12)
    tri = v[f]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert np.allclose(normals, cross / np.linalg.norm(cross, axis=1)[:, None], atol=1e-12)
    kept = mesh.reverse.copy()
    checked_mesh(*cylinder_mesh(5.0, 8.0, 16))
    assert np.array_equal(mesh.reverse, kept)
    given = facets.planning_mesh(v, f, None, mesh.reverse, mesh.normals)
    found = facets.planning_mesh(v, f)
    assert given.merged == found.merged and np.array_equal(given.faces, found.faces)
    assert np.array_equal(given.vertices, found.vertices) and len(given.faces) == 12
