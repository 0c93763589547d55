"""W6 for radial turn-mill work: the radius map r(theta, z), checked against closed forms, the
design (gouges), rapids through the bar, and the combined bar of the built-in sample."""
import math
import pickle

import numpy as np
import pytest
import trimesh
from manifold3d import Manifold

from kezuri.toolpath import simulate
from kezuri.toolpath.operations.turnmill import turnmill
from kezuri.toolpath.simulate import radiusmap
from kezuri.toolpath.ir.program import FEED, RAPID, Tool

BAR = turnmill.Stock(20.0, -30.0, 0.0)
BALL_R = 3.0


def radial_op(moves, r=BALL_R, start=(25.0, -15.0, 0.0), name="ring"):
    """A radial ball operation from (kind, X, Z, C) moves; start = (X, Z, C)."""
    kind = np.array([m[0] for m in moves])
    xyz = np.array([[m[1], 0.0, m[2]] for m in moves], float)
    c = np.array([m[3] for m in moves], float)
    feed = np.where(kind == RAPID, np.nan, 300.0)
    return turnmill.TurnMillOperation(name, Tool(1, "ball", 2 * r), 3000.0, kind, xyz, feed, rotary={"c": c},
                                      clearance_z=5.0, safe_z=5.0,
                                      start=np.array([start[0], 0.0, start[1]]), direction="radial")


def ring_groove(x_tip=15.0, z=-15.0, c_turn=360.0):
    """Feed in at C = 0, turn C once round, rapid out: a groove round the bar."""
    return radial_op([(FEED, x_tip, z, 0.0), (FEED, x_tip, z, c_turn), (RAPID, 25.0, z, c_turn)],
                     start=(25.0, z, 0.0))


def ring_volume(bar_radius, centre_radius, r):
    """Pappus: the shank's rectangle from the ball centre out to the bar, plus the ball's inner
    half disc (centroid 4r / 3pi inside the centre)."""
    rectangle = math.pi * (bar_radius ** 2 - centre_radius ** 2) * 2 * r
    half_disc = 2 * math.pi * (centre_radius - 4 * r / (3 * math.pi)) * math.pi * r * r / 2
    return rectangle + half_disc


@pytest.mark.parametrize("kernel", ["numba", "numpy"])
def test_ring_groove_volume_matches_pappus(kernel):
    result = simulate.simulate([ring_groove()], BAR, cell=0.1, tolerance=0.01, kernel=kernel)
    assert result.engine == "radiusmap"
    assert result.removed_volume_mm3 == pytest.approx(ring_volume(20.0, 18.0, BALL_R), rel=0.01)
    assert result.findings == []


def test_manifold_engine_turns_the_tool_with_c():
    """The exact-solid engine places the radial tool along its own axis at every move: the same
    ring groove, within 1 % of Pappus and of the radius map."""
    solid = simulate.simulate([ring_groove()], BAR, engine="manifold", tolerance=0.01)
    assert solid.engine == "manifold"
    assert solid.removed_volume_mm3 == pytest.approx(ring_volume(20.0, 18.0, BALL_R), rel=0.01)
    vertices, faces = solid.mesh()
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    rho = np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 1])
    groove = np.abs(mesh.vertices[:, 2] + 15.0) < 0.2
    assert rho[groove].min() == pytest.approx(15.0, abs=0.02)      # the ball's front at the tip radius
    assert solid.findings == []


def test_ring_groove_profile_is_the_ball():
    """Across the groove, the material radius is the ball's inner edge: 18 - sqrt(9 - dz^2)."""
    rm = simulate.simulate([ring_groove()], BAR, cell=0.05, tolerance=0.005).radiusmap
    z = rm.z()
    dz = z + 15.0
    inside = np.abs(dz) < BALL_R - 0.05
    expected = 18.0 - np.sqrt(BALL_R ** 2 - dz[inside] ** 2)
    for i in (0, rm.shape[0] // 3, rm.shape[0] - 1):
        assert np.allclose(rm.radii[i, inside], expected, atol=0.006)
    assert np.all(rm.radii[:, np.abs(dz) > BALL_R + 0.05] == 20.0)


def test_half_turn_cuts_half_the_ring():
    full = simulate.simulate([ring_groove()], BAR, cell=0.1, tolerance=0.01).removed_volume_mm3
    half = simulate.simulate([ring_groove(c_turn=180.0)], BAR, cell=0.1, tolerance=0.01)
    # Each end adds the half of the tool's cut that lies beyond the end plane; the two halves
    # make one whole plunge (the tool is symmetric about its own plane).
    plunge = simulate.simulate([ring_groove(c_turn=0.0)], BAR, cell=0.1, tolerance=0.01).removed_volume_mm3
    assert half.removed_volume_mm3 == pytest.approx(full / 2 + plunge, rel=0.01)
    rm = half.radiusmap
    z_row = rm.cells_of(np.array([0.0]), np.array([-15.0]))[1][0]
    theta = rm.theta()
    assert np.all(rm.radii[(theta > 0.3) & (theta < math.pi - 0.3), z_row] < 15.01)
    assert np.all(rm.radii[(theta > math.pi + 0.5) & (theta < 2 * math.pi - 0.5), z_row] == 20.0)


def test_kernels_agree():
    program = [ring_groove(), ring_groove(x_tip=12.0, z=-22.0, c_turn=-270.0)]
    a = simulate.simulate(program, BAR, cell=0.1, kernel="numba").radiusmap.radii
    b = simulate.simulate(program, BAR, cell=0.1, kernel="numpy").radiusmap.radii
    assert np.abs(a - b).max() < 1e-9


def cylinder_design(radius, z_min=-30.0, z_max=0.0):
    mesh = Manifold.cylinder(z_max - z_min, radius, radius, 256).translate((0, 0, z_min)).to_mesh64()
    return trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts), process=False)


def _kernels(kernel):
    from kezuri.toolpath.simulate.heightfield import compiled_kernels
    return compiled_kernels(kernel)


@pytest.mark.parametrize("kernel", ["numba", "numpy"])
def test_outer_radii_of_a_cylinder(kernel):
    design = cylinder_design(16.0, -25.0, -5.0)
    rm = radiusmap.grid(20.0, -30.0, 0.0, 0.1)
    outer = radiusmap.outer_radii(rm, np.asarray(design.vertices), np.asarray(design.faces), _kernels(kernel))
    within = (rm.z() > -25.0) & (rm.z() < -5.0)
    sag = 16.0 * (1 - math.cos(math.pi / 256))
    assert np.all(outer[:, within] <= 16.0 + 1e-9)
    assert np.all(outer[:, within] >= 16.0 - sag - 1e-9)
    assert np.all(outer[:, ~within] == 0.0)


def test_outer_radii_kernels_agree_bit_for_bit():
    """A cone off the axis and a sphere holding the axis (rays met from every side, segments
    across the angle's wrap): the compiled rays give the numpy path's radii exactly."""
    cone = Manifold.cylinder(20.0, 6.0, 2.0, 64).translate((9.0, -3.0, -25.0)).to_mesh64()
    ball = Manifold.sphere(4.0, 48).translate((1.0, 0.5, -12.0)).to_mesh64()
    rm = radiusmap.grid(20.0, -30.0, 0.0, 0.1)
    for mesh in (cone, ball):
        vertices, faces = np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts, np.int64)
        a = radiusmap.outer_radii(rm, vertices, faces, _kernels("numba"))
        b = radiusmap.outer_radii(rm, vertices, faces, None)
        assert (a > 0).sum() > 1000 and np.array_equal(a, b)


def test_one_millimetre_into_the_design_is_a_one_millimetre_gouge():
    design = cylinder_design(16.0)        # the groove's floor (tip radius 15) is 1 mm inside it
    result = simulate.simulate([ring_groove()], BAR, cell=0.05, tolerance=0.005, design=design)
    gouges = result.findings_of("gouge")
    assert len(gouges) == 1
    assert gouges[0].depth_mm == pytest.approx(1.0, abs=0.02)
    assert gouges[0].move in (0, 1)       # the plunge or the turn: both reach the floor
    assert gouges[0].z == pytest.approx(-15.0, abs=0.05)
    assert math.hypot(*gouges[0].xy) == pytest.approx(15.0, abs=0.02)
    clear = simulate.simulate([ring_groove()], BAR, cell=0.05, tolerance=0.005, design=cylinder_design(14.9))
    assert clear.findings_of("gouge") == []


def test_manifold_gouge_volume_is_the_design_cut_away():
    """The groove's floor is 1 mm inside a 16 mm design cylinder: the part of the ball's half disc
    inside radius 16 (a circle segment 1 mm high), turned once round (Pappus)."""
    r, h, centre = BALL_R, 1.0, 18.0
    half_angle = math.acos((r - h) / r)
    area = r * r * half_angle - (r - h) * math.sqrt(2 * r * h - h * h)
    offset = 4 * r * math.sin(half_angle) ** 3 / (3 * (2 * half_angle - math.sin(2 * half_angle)))
    expected = 2 * math.pi * (centre - offset) * area
    result = simulate.simulate([ring_groove()], BAR, engine="manifold", tolerance=0.01, design=cylinder_design(16.0))
    assert result.gouge_volume_mm3 == pytest.approx(expected, rel=0.02)
    clear = simulate.simulate([ring_groove()], BAR, engine="manifold", tolerance=0.01, design=cylinder_design(14.9))
    assert clear.gouge_volume_mm3 == pytest.approx(0.0, abs=0.5)


def test_rapid_into_the_bar_is_reported():
    op = radial_op([(RAPID, 15.0, -15.0, 0.0), (FEED, 15.0, -15.0, 90.0), (RAPID, 25.0, -15.0, 90.0)],
                   start=(25.0, -15.0, 0.0))
    rapids = simulate.simulate([op], BAR, cell=0.1).findings_of("rapid_in_material")
    assert [f.move for f in rapids] == [0]
    assert rapids[0].depth_mm == pytest.approx(5.0, abs=0.05)    # the ball's front reaches radius 15 in a 20 bar


def test_a_cell_too_fine_for_memory_is_refused():
    long_bar = turnmill.Stock(5.0, -10000.0, 0.0)       # a small end face, a huge side
    with pytest.raises(simulate.SimulationError, match="dexels round the bar"):
        simulate.simulate([ring_groove(x_tip=3.0)], long_bar, cell=0.05)


def test_radial_work_needs_a_bar_and_a_ball():
    with pytest.raises(simulate.SimulationError, match="cylinder stock"):
        simulate.simulate([ring_groove()], simulate.BoxStock(-20, -20, -30, 20, 20, 0))
    op = ring_groove()
    op.tool = Tool(1, "flat", 6.0)
    with pytest.raises(simulate.SimulationError, match="ball end mills"):
        simulate.simulate([op], BAR)


@pytest.fixture(scope="module")
def sample():
    vertices, faces, stock = turnmill.sample_part()
    plan = turnmill.plan(vertices, faces, stock)
    design = trimesh.Trimesh(vertices, faces, process=False)
    result = simulate.simulate(plan.program, stock, cell=0.1, design=design)
    return design, stock, result


def test_sample_part_is_cut_without_gouges_or_rapids(sample):
    design, stock, result = sample
    assert result.engine == "radiusmap+heightfield"
    assert result.findings == []
    to_remove = math.pi * stock.radius ** 2 * (stock.z_max - stock.z_min) - design.volume
    # Ball end mills leave the fillets in the inside corners: a few percent stays.
    assert 0.9 * to_remove < result.removed_volume_mm3 < to_remove


def test_sample_part_features_are_cut(sample):
    _, _, result = sample
    rm, hf = result.radiusmap, result.heightfield
    i, k = rm.cells_of(np.array([0.0]), np.array([-37.5]))
    assert rm.radii[i[0], k[0]] == pytest.approx(35.0, abs=0.05)      # the flat at x = 35, mid height
    i, k = rm.cells_of(np.array([2.0]), np.array([-16.0]))
    assert rm.radii[i[0], k[0]] == pytest.approx(36.0, abs=0.05)      # the groove floor
    j = np.argmin(np.abs(hf.y()))
    x = hf.x()
    assert hf.heights[np.argmin(np.abs(x - 20.0)), j] == pytest.approx(-6.0, abs=0.02)   # the end-face pocket
    assert rm.operation[i[0], k[0]] >= 0 and hf.operation[np.argmin(np.abs(x - 20.0)), j] >= 2


def test_sample_bar_mesh_is_closed_and_holds_the_material(sample):
    _, stock, result = sample
    vertices, faces = result.mesh()
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    assert mesh.is_watertight
    bar = math.pi * stock.radius ** 2 * (stock.z_max - stock.z_min)
    assert bar - mesh.volume == pytest.approx(result.removed_volume_mm3, rel=0.03)
    colours = result.operation_at(vertices)
    depth = result.depth_at(vertices)
    deep = colours[depth > 0.5]
    assert np.mean(deep >= 0) > 0.99           # the rest sit on the walls of pocket rims
    assert set(np.unique(deep)) <= {-1, 0, 1, 2, 3}
    assert {0, 1}.intersection(deep) and {2, 3}.intersection(deep)     # radial and axial surfaces


def test_result_travels_between_processes(sample):
    _, _, result = sample
    back = pickle.loads(pickle.dumps(result))
    assert np.array_equal(back.radiusmap.radii, result.radiusmap.radii)
    assert back.removed_volume_mm3 == result.removed_volume_mm3


def test_turned_mesh_joins_the_untouched_bar_to_the_cut_end():
    """A bar (radius 20, z -30..0) with a groove of radius 17 over z -20..-10 on half its turn, and
    a 10 x 10 mm pocket 3 mm deep in its end face: the bar below the pocket joins the boolean's
    result at a ring, and the mesh is closed, its volume the bar's mesh alone (no boolean) less
    the pocket's (walls sloped between cell centres), its triangles below the pocket the bar's own."""
    from kezuri.toolpath.simulate.meshes import turned_mesh
    from kezuri.toolpath.simulate.stock import CylinderStock, HeightField

    n_theta, n_z = 64, 60
    radii = np.full((n_theta, n_z), 20.0)
    radii[: n_theta // 2, 20:40] = 17.0                      # z cells 20..39: z -20..-10
    rm = radiusmap.RadiusMap(20.0, -30.0, 0.5, 2 * math.pi / n_theta, radii, np.full(radii.shape, -1))
    heights = np.zeros((80, 80), np.float32)
    heights[35:45, 35:45] = -3.0                              # cells 1 mm: x, y in [-5, 5]
    xy = (np.arange(80) + 0.5) - 40.0
    inside = np.hypot(xy[:, None], xy[None, :]) < 20.0
    hf = HeightField(-40.0, -40.0, 1.0, 1.0, heights, inside, 0.0, -30.0)
    vertices, faces = turned_mesh(rm, hf, CylinderStock(20.0, 30.0), None)
    mesh = trimesh.Trimesh(vertices, faces, process=True)
    assert mesh.is_watertight and mesh.is_winding_consistent
    plain_bar = trimesh.Trimesh(*radiusmap.mesh(rm, -30.0, 0.0), process=True)   # no boolean
    assert plain_bar.is_watertight
    bar = plain_bar.volume
    # The relief's vertices stand at the cell centres: the pocket's walls slope from its floor's
    # outer centres (half width 4.5) to the uncut centres 1 mm above the end face (5.5), so at
    # depth 3 - t the half width is 4.5 + t / 4: the integral of (9 + t / 2)^2 over t in [0, 3]
    # (the corners' diagonals make it a little less).
    pocket = 2.0 / 3.0 * (10.5 ** 3 - 9.0 ** 3)
    assert bar - mesh.volume == pytest.approx(pocket, abs=1.0)
    def triangles_below(v, f):      # each triangle's corners in float32, sorted; then the rows sorted
        t = np.asarray(v, np.float32)[np.asarray(f)]
        t = t[t[:, :, 2].max(axis=1) < -4.0]
        t = np.array([sorted(map(tuple, tri)) for tri in t]).reshape(-1, 9)
        return t[np.lexsort(t.T[::-1])]

    ours, plain = triangles_below(vertices, faces), triangles_below(*radiusmap.mesh(rm, -30.0, 0.0))
    assert len(ours) > 0.8 * len(radiusmap.mesh(rm, -30.0, 0.0)[1])
    assert np.array_equal(ours, plain)



def _depth_pictures(meshes, tilt: float):
    """(view, [depth buffer of each (vertices, faces)]): the bar r 20, z -30..0 framed at ``tilt``."""
    from kezuri.toolpath.pictures.picture import Picture, View
    view = View(np.array([[-20.0, -20, -30], [20, 20, 0]]), (0, 0, 400, 400), tilt)
    depths = []
    for vertices, faces in meshes:
        picture = Picture(400, 400)
        picture.triangles(view, vertices, faces, (200, 200, 200))
        depths.append(picture.depth)
    return view, depths


def test_turned_surface_looks_like_the_closed_mesh():
    """The picture's surface (no boolean) of the bar of the test above looks like the closed mesh:
    seen from above, the same pixels are covered (but for a sliver along the rim, where the mesh's
    end face is a 64-gon and the surface's a finer polygon on the same circle), at the same
    height but on the pocket's walls (the mesh's walls start at the end face 3/4 of the way from
    the floor's outer cell centres to the next ones, the surface's at those: at most 0.75 mm
    apart); seen from the side, nearly all pixels alike."""
    from kezuri.toolpath.simulate.meshes import turned_mesh, turned_surface
    from kezuri.toolpath.simulate.stock import CylinderStock, HeightField

    n_theta, n_z = 64, 60
    radii = np.full((n_theta, n_z), 20.0)
    radii[: n_theta // 2, 20:40] = 17.0
    rm = radiusmap.RadiusMap(20.0, -30.0, 0.5, 2 * math.pi / n_theta, radii, np.full(radii.shape, -1))
    heights = np.zeros((80, 80), np.float32)
    heights[35:45, 35:45] = -3.0
    xy = (np.arange(80) + 0.5) - 40.0
    hf = HeightField(-40.0, -40.0, 1.0, 1.0, heights, np.hypot(xy[:, None], xy[None, :]) < 20.0, 0.0, -30.0)
    stock = CylinderStock(20.0, 30.0)
    meshes = turned_mesh(rm, hf, stock, None), turned_surface(rm, hf, stock, None)
    for tilt in (0.0, 72.0):
        view, depths = _depth_pictures(meshes, tilt)
        covered = np.isfinite(depths[0])
        both = covered & np.isfinite(depths[1])
        apart = np.abs(np.where(both, depths[0], 0.0) - np.where(both, depths[1], 0.0))
        if tilt == 0.0:
            assert np.count_nonzero(covered != np.isfinite(depths[1])) < 2 * math.pi * 20.0 * view.scale * 0.25
            x = (np.arange(400) + 0.5 - view.px) / view.scale + view.cx
            y = -(np.arange(400) + 0.5 - view.py) / view.scale + view.cy
            side = np.maximum(np.abs(x)[None, :], np.abs(y)[:, None])      # [row, column]
            walls = (side > 4.5 - 1.5 / view.scale) & (side < 5.5 + 1.5 / view.scale)
            assert apart[~walls].max() < 1e-9
            assert apart[walls].max() <= 0.75
        else:
            assert np.count_nonzero(covered != np.isfinite(depths[1])) < 0.001 * covered.sum()
            assert np.count_nonzero(apart > 0.01) < 0.03 * both.sum()


def test_turned_surface_of_a_faced_bar_keeps_its_edge():
    """A bar (radius 20) whose whole end face is cut 1 mm down (the cells outside the bar stay
    uncut, as the simulation leaves them): nothing of the picture's surface stands above the new
    face, and seen from above the face covers the bar to its edge; the closed mesh is the bar
    1 mm shorter (its volume that of the radius map's 2513-gon prism)."""
    from kezuri.toolpath.pictures.picture import Picture, View
    from kezuri.toolpath.simulate.meshes import turned_mesh, turned_surface
    from kezuri.toolpath.simulate.stock import CylinderStock, HeightField

    rm = radiusmap.grid(20.0, -30.0, 0.0, 0.25)
    xy = -20.0 + (np.arange(160) + 0.5) * 0.25
    inside = np.hypot(xy[:, None], xy[None, :]) <= 20.0
    heights = np.where(inside, -1.0, -np.inf).astype(np.float32)
    hf = HeightField(-20.0, -20.0, 0.25, 0.25, heights, inside, 0.0, -30.0)
    vertices, faces = turned_surface(rm, hf, CylinderStock(20.0, 30.0), None)
    assert vertices[:, 2].max() <= -1.0 + 1e-9
    assert len(faces) < len(radiusmap.mesh(rm, -30.0, 0.0)[1]) * 1.2     # the flat face in few tiles
    view = View(np.array([[-20.0, -20, -30], [20, 20, 0]]), (0, 0, 400, 400), 0.0)
    picture = Picture(400, 400)
    picture.triangles(view, vertices, faces, (200, 200, 200))
    x = (np.arange(400) + 0.5 - view.px) / view.scale + view.cx
    y = -(np.arange(400) + 0.5 - view.py) / view.scale + view.cy
    within = np.hypot(x[None, :], y[:, None]) < 20.0 - 0.02
    assert np.allclose(picture.depth[within], -1.0)
    closed = trimesh.Trimesh(*turned_mesh(rm, hf, CylinderStock(20.0, 30.0), None), process=True)
    assert closed.is_watertight and closed.vertices[:, 2].max() <= -1.0 + 1e-5
    n = rm.shape[0]
    assert closed.volume == pytest.approx(n / 2 * 20.0 ** 2 * math.sin(2 * math.pi / n) * 29.0, rel=1e-5)


def test_turned_surface_merges_the_untouched_side():
    """A bar with a groove on part of its turn and no axial cut: the picture's surface draws the
    same pixels at the same depths as the closed mesh from above, at 72 degrees and from the side,
    with the untouched strips of its side one quad each (far fewer triangles)."""
    from kezuri.toolpath.simulate.meshes import turned_mesh, turned_surface
    from kezuri.toolpath.simulate.stock import CylinderStock

    rm = radiusmap.grid(20.0, -30.0, 0.0, 0.25)
    rm.radii[:100, 40:60] = 17.0
    meshes = turned_mesh(rm, None, CylinderStock(20.0, 30.0), None), turned_surface(rm, None, CylinderStock(20.0, 30.0),
                                                                                       None)
    assert len(meshes[1][1]) < len(meshes[0][1]) / 10
    for tilt in (0.0, 72.0, 90.0):
        _, depths = _depth_pictures(meshes, tilt)
        covered = np.isfinite(depths[0])
        assert np.array_equal(covered, np.isfinite(depths[1]))
        assert np.abs(depths[0][covered] - depths[1][covered]).max() < 1e-9
