"""W6: material removal (height field and manifold engines) against closed forms, and the
safety checks (gouges, rapids in material, travel limits, plunges)."""
import importlib.util
import math
import os

import numpy as np
import pytest
import trimesh

from kezuri.toolpath import simulate as sim
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program, Tool

FLAT6 = Tool(1, "flat", 6.0)
BALL6 = Tool(2, "ball", 6.0)
BULL6 = Tool(3, "bull", 6.0, corner_radius=1.0)
VBIT6 = Tool(4, "vbit", 6.0)          # 90 degrees
DRILL6 = Tool(5, "drill", 6.0)        # 118 degrees
BOX = (0, 0, -10, 40, 40, 0)
NUMBA = importlib.util.find_spec("numba") is not None and os.environ.get("KEZURI_NO_NUMBA") != "1"


@pytest.fixture(params=["numpy", "numba"])
def kernel(request):
    """The height field kernel under test (numba where it is installed and not switched off)."""
    if request.param == "numba" and not NUMBA:
        pytest.skip("the numba kernel is not available")
    return request.param


def operation(tool, points, start, kinds=None, center=None, c=None, name="op"):
    """An operation from end points (n, 3); every move a feed unless ``kinds`` says otherwise."""
    points = np.asarray(points, float)
    n = len(points)
    kinds = np.full(n, FEED) if kinds is None else np.asarray(kinds)
    feed = np.where(kinds == RAPID, np.nan, 500.0)
    return Operation(name, tool, 10000, kinds, points, feed, center=center,
                     rotary={} if c is None else {"c": np.asarray(c, float)}, start=np.asarray(start, float))


def slot(tool, depth, length=20.0, y=20.0):
    """Feed down at (10, y), along X for ``length``, rapid up."""
    points = [[10, y, -depth], [10 + length, y, -depth], [10 + length, y, 5.0]]
    return operation(tool, points, start=[10, y, 5.0], kinds=[FEED, FEED, RAPID])


def both_engines(ops, stock, cell=0.1, kernel="auto"):
    return [sim.simulate(ops, stock, engine=engine, cell=cell, tolerance=0.01, kernel=kernel)
            for engine in ("heightfield", "manifold")]


def assert_close(results, expected, rel=0.01):
    volumes = [r.removed_volume_mm3 for r in results]
    for v in volumes:
        assert v == pytest.approx(expected, rel=rel)
    assert volumes[0] == pytest.approx(volumes[1], rel=rel)


# ----- closed forms -------------------------------------------------------------------------

def test_flat_end_slot_is_a_stadium_times_depth(kernel):
    length, d, depth = 20.0, 6.0, 2.0
    expected = (length * d + math.pi * d * d / 4) * depth
    assert_close(both_engines(slot(FLAT6, depth, length), BOX, kernel=kernel), expected)


def test_ball_end_slot_is_half_a_capsule(kernel):
    r, length = 3.0, 20.0
    expected = length * math.pi * r * r / 2 + 2 / 3 * math.pi * r ** 3
    assert_close(both_engines(slot(BALL6, r, length), BOX, kernel=kernel), expected)


def test_bull_nose_slot_matches_its_profile(kernel):
    r, rc, depth, length = 3.0, 1.0, 2.0, 20.0
    flat = r - rc
    corner = rc * rc * (1 - math.pi / 4)          # material a corner leaves in the section
    corner_r = (rc * rc * (flat + rc / 2) - math.pi * rc * rc / 4 * (flat + 4 * rc / (3 * math.pi))) / corner
    section = 2 * r * depth - 2 * corner
    ends = math.pi * r * r * depth - 2 * math.pi * corner_r * corner   # the two half ends: one tool
    results = both_engines(slot(BULL6, depth, length), BOX, kernel=kernel)
    assert_close(results, length * section + ends)
    # across the middle of the slot every cell is the profile: flat, then the corner's arc
    hf = results[0].heightfield
    column = np.argmin(np.abs(hf.x() - 20.05))
    across = np.abs(hf.y() - 20.0)
    inside = across < r
    off = np.maximum(across[inside] - flat, 0.0)
    profile = -depth + rc - np.sqrt(rc * rc - off * off)
    np.testing.assert_allclose(hf.heights[column, inside], profile, atol=1e-5)


def test_v_bit_groove_is_a_triangle_prism_plus_a_cone(kernel):
    # 90 degrees: the groove is as deep as it is half wide; its two half-cone ends make one cone.
    depth, length = 2.0, 20.0
    expected = length * depth * depth + math.pi * depth ** 3 / 3
    results = both_engines(slot(VBIT6, depth, length), BOX, kernel=kernel)
    assert_close(results, expected)
    # across the middle of the groove every cell is exact: the flank, one mm up per mm aside
    hf = results[0].heightfield
    column = np.argmin(np.abs(hf.x() - 20.05))
    across = hf.y() - 20.0
    inside = np.abs(across) < depth
    np.testing.assert_allclose(hf.heights[column, inside], -depth + np.abs(across[inside]), atol=1e-5)


def test_v_bit_ramps_match_the_cone_stamped_densely_along_them(kernel):
    # a gentle ramp that ends deeper than the cone is tall (3 mm: the rim cuts beside it) and a
    # ramp steeper than the flank: the height field is the exact lower envelope, so it lies
    # between the cone stamped at 4001 places along each move and that less the V-groove
    # between two stamps (slope * spacing / 2)
    tool, cell = VBIT6, 0.2
    moves = [([10.0, 12.0, -1.0], [28.0, 20.0, -4.5]), ([12.0, 30.0, -0.5], [13.0, 31.0, -3.0])]
    points = [moves[0][0], moves[0][1], [28.0, 20.0, 5.0], [12.0, 30.0, 5.0], moves[1][0], moves[1][1],
              [13.0, 31.0, 5.0]]
    op = operation(tool, points, start=[10.0, 12.0, 5.0], kinds=[FEED, FEED, RAPID, RAPID, FEED, FEED, RAPID])
    hf = sim.simulate(op, BOX, cell=cell, kernel=kernel).heightfield
    x, y = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    stamped = np.full(hf.shape, hf.top)
    worst_groove = 0.0
    for a, b in moves:
        a, b = np.asarray(a), np.asarray(b)
        places = a + np.linspace(0.0, 1.0, 4001)[:, None] * (b - a)
        worst_groove = max(worst_groove, np.hypot(*(b - a)[:2]) / 4000 / 2)     # slope 1: 90 degrees
        for px, py, pz in places:
            d = np.hypot(x - px, y - py)
            stamped = np.minimum(stamped, np.where(d <= tool.radius, pz + d, np.inf))
    assert np.all(hf.heights <= stamped + 1e-5)
    assert np.all(hf.heights >= stamped - worst_groove - 1e-5)
    assert (hf.heights < hf.top).sum() > 1000


def test_drilled_hole_is_a_cylinder_on_a_cone(kernel):
    tip = 3.0 / math.tan(math.radians(59))     # height of the 118 degree point
    depth = 5.0
    op = operation(DRILL6, [[20, 20, -depth], [20, 20, 5.0]], start=[20, 20, 5.0], kinds=[FEED, RAPID])
    expected = math.pi * 9 * (depth - tip) + math.pi * 9 * tip / 3
    results = both_engines(op, BOX, kernel=kernel)
    assert_close(results, expected)
    hf = results[0].heightfield
    centre = np.argmin(np.abs(hf.x() - 20.05)), np.argmin(np.abs(hf.y() - 20.05))
    assert hf.heights[centre] == pytest.approx(-depth + 0.05 * math.sqrt(2) / math.tan(math.radians(59)), abs=1e-5)


def test_ring_groove_with_the_table_turning_is_an_annulus(kernel):
    # C-X-Z: the tool held at X = -30 (radius 30 on the part) while C turns a full turn.
    op = operation(FLAT6, [[-30, 0, -2.0], [-30, 0, -2.0], [-30, 0, 5.0]], start=[-30, 0, 5.0],
                   c=[0.0, 360.0, 360.0], kinds=[FEED, FEED, RAPID])
    expected = math.pi * (33 ** 2 - 27 ** 2) * 2.0
    results = both_engines(op, sim.CylinderStock(radius=50, height=20), cell=0.2, kernel=kernel)
    assert_close(results, expected)


def test_quarter_turn_of_c_cuts_a_quarter_ring_at_the_right_place(kernel):
    # C = angle of the part point from the -X axis: C 0..90 at X = -30 sweeps the third quadrant.
    op = operation(FLAT6, [[-30, 0, -2.0], [-30, 0, -2.0]], start=[-30, 0, 5.0], c=[0.0, 90.0])
    result = sim.simulate(op, sim.CylinderStock(radius=50, height=20), cell=0.2, kernel=kernel)
    expected = math.pi * (33 ** 2 - 27 ** 2) / 4 * 2.0 + math.pi * 9 * 2.0   # plus the two half ends
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=0.01)
    hf = result.heightfield
    i = np.argmin(np.abs(hf.x() + 30 * math.cos(math.radians(45))))
    j = np.argmin(np.abs(hf.y() + 30 * math.sin(math.radians(45))))
    assert hf.heights[i, j] == pytest.approx(-2.0, abs=1e-4)
    assert hf.heights[np.argmin(np.abs(hf.x() - 21.2)), np.argmin(np.abs(hf.y() + 21.2))] == 0.0


def test_helix_then_flat_circle_leaves_an_annulus(kernel):
    # Two G3 full circles around (20, 20), radius 10: a helix down 2 mm, then one flat turn.
    points = [[30, 20, 0.0], [30, 20, -2.0], [30, 20, -2.0], [30, 20, 5.0]]
    center = [[np.nan] * 3, [20, 20, 0], [20, 20, 0], [np.nan] * 3]
    op = operation(FLAT6, points, start=[30, 20, 5.0], kinds=[FEED, ARC_CCW, ARC_CCW, RAPID], center=center)
    expected = math.pi * (13 ** 2 - 7 ** 2) * 2.0
    assert_close(both_engines(op, BOX, kernel=kernel), expected)


def test_helix_floor_is_a_ramp(kernel):
    # After one helical turn alone, the floor under the path descends with the angle.
    points = [[30, 20, 0.0], [30, 20, -2.0]]
    op = operation(FLAT6, points, start=[30, 20, 0.0], kinds=[FEED, ARC_CCW], center=[[np.nan] * 3, [20, 20, 0]])
    hf = sim.simulate(op, BOX, cell=0.1, kernel=kernel).heightfield
    for angle in (90, 180, 270):
        x = 20 + 10 * math.cos(math.radians(angle))
        y = 20 + 10 * math.sin(math.radians(angle))
        i, j = np.argmin(np.abs(hf.x() - x)), np.argmin(np.abs(hf.y() - y))
        # going down, the flat end is lowest over a point when its rim leaves it: the centre is
        # then a 3 mm chord (2 asin(3 / 20) of the turn) further on
        leave = angle + math.degrees(2 * math.asin(3 / 20))
        assert hf.heights[i, j] == pytest.approx(-2.0 * leave / 360, abs=0.002)


def test_arc_slot_is_half_an_annulus_plus_two_half_ends(kernel):
    # G2 half circle around (20, 20), radius 10, from (30, 20) to (10, 20), 2 mm deep.
    points = [[30, 20, -2.0], [10, 20, -2.0], [10, 20, 5.0]]
    center = [[np.nan] * 3, [20, 20, -2.0], [np.nan] * 3]
    op = operation(FLAT6, points, start=[30, 20, 5.0], kinds=[FEED, ARC_CW, RAPID], center=center)
    expected = (math.pi * (13 ** 2 - 7 ** 2) / 2 + math.pi * 9) * 2.0
    results = both_engines(op, BOX, kernel=kernel)
    assert_close(results, expected)
    # clockwise from (30, 20) to (10, 20) passes below the centre
    hf = results[0].heightfield
    assert hf.heights[np.argmin(np.abs(hf.x() - 20)), np.argmin(np.abs(hf.y() - 10))] == pytest.approx(-2.0)
    assert hf.heights[np.argmin(np.abs(hf.x() - 20)), np.argmin(np.abs(hf.y() - 30))] == 0.0


def test_manifold_joins_nearly_straight_moves_without_cutting_more():
    # 200 short moves along a gentle wave: joined into a few hulls of a slightly smaller tool.
    x = np.linspace(5, 35, 201)
    points = np.column_stack([x, np.full_like(x, 20.0), -2.0 - 0.3 * np.sin(x / 3)])
    heightfield, solid = both_engines(operation(BALL6, points[1:], start=points[0]), BOX)
    assert solid.removed_volume_mm3 <= heightfield.removed_volume_mm3 * 1.001
    assert solid.removed_volume_mm3 == pytest.approx(heightfield.removed_volume_mm3, rel=0.01)


def test_program_of_several_operations_removes_the_union(kernel):
    program = Program("two slots", [slot(FLAT6, 2.0, y=10.0), slot(FLAT6, 2.0, y=30.0)])
    single = (20 * 6 + math.pi * 9) * 2
    assert sim.simulate(program, BOX, kernel=kernel).removed_volume_mm3 == pytest.approx(2 * single, rel=0.01)


# ----- the height field is the exact envelope ------------------------------------------------

def sampled_envelope(points, tool, hf, step=0.002):
    """Reference: the tool stamped at points every ``step`` mm along every straight move."""
    gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    lowest = np.full(gx.shape, np.inf)
    r = tool.radius
    for a, b in zip(points[:-1], points[1:]):
        for t in np.linspace(0, 1, int(np.linalg.norm(b - a) / step) + 2):
            p = a + t * (b - a)
            i = slice(*np.searchsorted(hf.x(), [p[0] - r, p[0] + r]))
            j = slice(*np.searchsorted(hf.y(), [p[1] - r, p[1] + r]))
            d = np.hypot(gx[i, j] - p[0], gy[i, j] - p[1])
            if tool.kind == "ball":
                h = np.where(d <= r, r - np.sqrt(np.maximum(r * r - d * d, 0)), np.inf)
            else:
                h = np.where(d <= r, 0.0, np.inf)
            lowest[i, j] = np.minimum(lowest[i, j], p[2] + h)
    return np.minimum(lowest, hf.top)


@pytest.mark.parametrize("tool", [BALL6, FLAT6], ids=["ball", "flat"])
def test_height_field_matches_a_densely_sampled_sweep(tool, kernel):
    rng = np.random.default_rng(7)
    points = np.cumsum(rng.normal(0, 1.2, (8, 3)), axis=0)
    points[:, :2] += 10 - points[:, :2].mean(axis=0)
    points[:, 2] = -1.0 - np.abs(points[:, 2]) * 0.4
    points = np.vstack([points, [[points[-1, 0], points[-1, 1], -3.5]], [[12, 9, -0.5]]])  # a plunge, a ramp
    op = operation(tool, points[1:], start=points[0])
    hf = sim.simulate(op, (0, 0, -10, 20, 20, 0), cell=0.1, kernel=kernel).heightfield
    reference = sampled_envelope(points, tool, hf)
    # exact up to the reference's own sampling (it can only sit higher)
    assert np.max(hf.heights - reference) < 2e-4
    assert np.min(hf.heights - reference) > -5e-3


# ----- safety checks -----------------------------------------------------------------------------

def test_cutting_one_mm_below_a_design_plane_is_a_one_mm_gouge(kernel):
    op = slot(FLAT6, 2.0)
    result = sim.simulate(op, BOX, kernel=kernel, design=-1.0)
    gouges = result.findings_of("gouge")
    assert len(gouges) == 1
    assert gouges[0].depth_mm == pytest.approx(1.0, abs=0.1)
    assert gouges[0].move in (0, 1)           # the plunge or the slot: both reach -2
    assert 7 - 0.1 <= gouges[0].xy[0] <= 33 + 0.1 and abs(gouges[0].xy[1] - 20) <= 3.1


def test_ball_gouge_names_the_move_that_went_deepest(kernel):
    points = [[10, 20, -1.0], [30, 20, -1.0], [30, 20, -2.0], [35, 20, -2.0]]
    op = operation(BALL6, points, start=[10, 20, 5.0])
    gouge, = sim.check(op, BOX, kernel=kernel, design=-1.5)
    assert gouge.kind == "gouge"
    assert gouge.depth_mm == pytest.approx(0.5, abs=0.01)
    assert gouge.move in (2, 3) and gouge.xy[0] >= 30 - 0.1


def test_design_as_a_function_and_as_a_mesh(kernel):
    op = slot(FLAT6, 2.0)
    by_function = sim.check(op, BOX, kernel=kernel, design=lambda x, y: np.where(x > 25, -1.0, -3.0))
    assert by_function[0].depth_mm == pytest.approx(1.0, abs=1e-3) and by_function[0].xy[0] > 25
    part = trimesh.creation.box(extents=(40, 40, 9), transform=trimesh.transformations.translation_matrix(
        (20, 20, -5.5)))                      # a block whose top is z = -1
    by_mesh = sim.check(op, BOX, kernel=kernel, design=part)
    assert by_mesh[0].kind == "gouge" and by_mesh[0].depth_mm == pytest.approx(1.0, abs=1e-3)
    assert sim.check(op, BOX, kernel=kernel, design=-2.0) == []


def test_keep_regions_forbid_any_cut(kernel):
    op = slot(FLAT6, 2.0)
    keep = np.array([[20, 0], [25, 0], [25, 40], [20, 40]], float)
    gouge, = sim.check(op, BOX, kernel=kernel, keep_regions=[keep])
    assert gouge.depth_mm == pytest.approx(2.0, abs=1e-3) and 20 <= gouge.xy[0] <= 25
    # a floor per region: cutting to -2 where -2.5 is allowed is fine
    assert sim.check(op, BOX, kernel=kernel, keep_regions=[(keep, -2.5)]) == []
    assert sim.check(op, BOX, kernel=kernel, keep_regions=[np.array([[0, 0], [5, 0], [5, 5]], float)]) == []


def test_rapid_through_the_stock_is_reported_with_its_move_index(kernel):
    points = [[5, 5, 5.0], [5, 5, -1.0], [35, 5, -1.0], [35, 5, 5.0], [35, 35, 5.0]]
    op = operation(FLAT6, points, start=[5, 5, 10.0], kinds=[RAPID, FEED, RAPID, RAPID, RAPID])
    rapids = sim.check(op, BOX, kernel=kernel)
    assert [(f.kind, f.move) for f in rapids] == [("rapid_in_material", 2)]
    assert rapids[0].depth_mm == pytest.approx(1.0, abs=1e-3)


def test_rapids_in_air_or_in_cut_material_are_fine(kernel):
    # Feed a slot, retract straight up, rapid back along the slot inside it: no material left there.
    points = [[10, 20, -2.0], [30, 20, -2.0], [30, 20, -1.0], [10, 20, -1.0], [10, 20, 5.0], [0, 0, 5.0]]
    op = operation(BALL6, points, start=[10, 20, 5.0], kinds=[FEED, FEED, RAPID, RAPID, RAPID, RAPID])
    assert sim.check(op, BOX, kernel=kernel) == []


def test_moves_outside_the_travel_are_reported():
    op = slot(FLAT6, 2.0, length=25.0)            # runs to X = 35
    found = sim.check(op, BOX, travel={"x": (0, 30), "z": (-50, 50)})
    assert [(f.kind, f.move) for f in found] == [("travel", 1)]
    assert "X" in found[0].message and "30" in found[0].message
    rotary = operation(FLAT6, [[-30, 0, -1.0]], start=[-30, 0, 5.0], c=[400.0])
    found = sim.check(rotary, sim.CylinderStock(50, 20), travel={"c": (-360, 360)})
    assert [(f.kind, f.move) for f in found] == [("travel", 0)]


def test_arcs_are_checked_along_their_path_not_only_at_their_ends():
    # A CCW half circle from (30, 20) to (10, 20) about (20, 20) bulges to Y = 30.
    op = operation(FLAT6, [[30, 20, 1.0], [10, 20, 1.0]], start=[30, 20, 5.0], kinds=[FEED, ARC_CCW],
                   center=[[np.nan] * 3, [20, 20, 1.0]])
    found = sim.check(op, BOX, travel={"y": (0, 25)})
    assert [(f.kind, f.move) for f in found] == [("travel", 1)]


def test_plunging_with_a_tool_that_cannot_plunge(kernel):
    down = [[20, 20, 2.0], [20, 20, -2.0], [30, 20, -2.0]]
    bull = sim.check(operation(BULL6, down, start=[20, 20, 5.0]), BOX, kernel=kernel)
    assert [(f.kind, f.move) for f in bull] == [("plunge", 1)]
    assert sim.check(operation(FLAT6, down, start=[20, 20, 5.0]), BOX, kernel=kernel) == []
    banned = sim.check(operation(FLAT6, down, start=[20, 20, 5.0]), BOX, kernel=kernel, no_plunge_tools={1})
    assert [(f.kind, f.move) for f in banned] == [("plunge", 1)]
    ramp = [[20, 20, 2.0], [30, 20, -2.0]]
    assert sim.check(operation(BULL6, ramp, start=[20, 20, 5.0]), BOX, kernel=kernel) == []
    assert sim.can_plunge(Tool(9, "drill", 5.0)) and not sim.can_plunge(BULL6)


# ----- result, mesh, progress ----------------------------------------------------------------------

def test_height_field_mesh_is_closed_and_holds_the_remaining_volume():
    result = sim.simulate(slot(BALL6, 3.0), BOX, cell=0.25)
    vertices, faces = result.mesh()
    mesh = trimesh.Trimesh(vertices, faces, process=True)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume == pytest.approx(40 * 40 * 10 - result.removed_volume_mm3, rel=0.002)
    pooled = trimesh.Trimesh(*result.mesh(max_cells=2000), process=True)
    assert pooled.is_watertight and len(pooled.faces) < len(mesh.faces) / 5
    assert pooled.volume < mesh.volume                      # min-pooling shows the deepest cut


def test_cylinder_stock_mesh_and_manifold_solid():
    op = operation(FLAT6, [[-30, 0, -2.0], [-30, 0, -2.0]], start=[-30, 0, 5.0], c=[0.0, 180.0])
    for engine in ("heightfield", "manifold"):
        result = sim.simulate(op, sim.CylinderStock(50, 20), engine=engine, cell=0.5)
        mesh = trimesh.Trimesh(*result.mesh(), process=True)
        assert mesh.is_watertight
        assert mesh.volume == pytest.approx(math.pi * 50 ** 2 * 20 - result.removed_volume_mm3, rel=0.003)


def test_progress_is_reported_and_can_cancel(kernel):
    seen = []
    sim.simulate(slot(FLAT6, 2.0), BOX, kernel=kernel, progress=seen.append)
    assert seen and seen[-1] == pytest.approx(1.0) and seen == sorted(seen)
    for engine in sim.ENGINES:
        with pytest.raises(sim.SimulationCancelled):
            sim.simulate(slot(FLAT6, 2.0), BOX, kernel=kernel, engine=engine, progress=lambda f: False)


def test_result_reports_engine_cell_kernel_and_time(kernel):
    result = sim.simulate(slot(FLAT6, 2.0), BOX, cell=0.2, kernel=kernel)
    assert result.engine == "heightfield" and result.cell == pytest.approx(0.2) and result.seconds > 0
    assert result.kernel == kernel
    solid = sim.simulate(slot(FLAT6, 2.0), BOX, engine="manifold", kernel=kernel)
    assert solid.engine == "manifold" and solid.cell is None and solid.tolerance == 0.03
    assert solid.kernel == kernel                     # its safety checks ran on that kernel


# ----- the two height field kernels ------------------------------------------------------------------

def random_operation(rng, tool, name, n=50):
    """A random walk over a 60 x 60 mm box at -0.5..-4 mm, half its moves level: feeds, arcs
    (their centres beside the chord, so some spiral), plunges, and rapids, some of them through
    the material."""
    xy = np.clip(30 + np.cumsum(rng.normal(0, 2.5, (n, 2)), axis=0), 3, 57)
    z = -rng.uniform(0.5, 4.0, n)
    kinds = rng.choice([FEED, FEED, ARC_CW, ARC_CCW], n)
    special = rng.choice(n - 1, 6, replace=False) + 1
    plunges, rapids = special[:4], special[4:]
    xy[plunges] = xy[plunges - 1]                       # straight down (or up)
    kinds[plunges] = FEED
    kinds[rapids] = RAPID
    previous = np.vstack([xy[:1], xy[:-1]])
    chord = xy - previous
    center = np.full((n, 3), np.nan)
    arcs = (kinds == ARC_CW) | (kinds == ARC_CCW)
    center[arcs, :2] = (xy + previous)[arcs] / 2 + rng.uniform(-1, 1, (arcs.sum(), 1)) * chord[arcs][:, ::-1] * [1, -1]
    center[arcs, 2] = 0.0
    for i in np.flatnonzero(rng.random(n) < 0.5)[1:]:   # about half the moves hold their depth
        z[i] = z[i - 1]
    return operation(tool, np.column_stack([xy, z]), start=[xy[0, 0], xy[0, 1], 5.0], kinds=kinds, center=center,
                     name=name)


@pytest.mark.skipif(not NUMBA, reason="the numba kernel is not available")
def test_both_kernels_give_the_same_heights_and_findings():
    rng = np.random.default_rng(11)
    tools = [BALL6, FLAT6, Tool(7, "bull", 8.0, corner_radius=2), VBIT6, DRILL6, Tool(8, "ball", 3.0)]
    program = Program("mixed", [random_operation(rng, tool, f"op{i}") for i, tool in enumerate(tools)])
    ring = operation(BULL6, [[-20, 0, -1.5], [-20, 0, -1.5], [-24, 0, -3.5], [-24, 0, 5.0]], start=[-20, 0, 5.0],
                     c=[0.0, 200.0, 300.0, 300.0], kinds=[FEED, FEED, FEED, RAPID])
    cases = [(program, (0, 0, -10, 60, 60, 0), 0.07), (ring, sim.CylinderStock(30, 10), 0.1)]
    kinds = []
    for ops, stock, cell in cases:
        numpy, numba = (sim.simulate(ops, stock, cell=cell, tolerance=0.1, design=-3.0, no_plunge_tools={7},
                                     kernel=kernel) for kernel in ("numpy", "numba"))
        assert (numpy.kernel, numba.kernel) == ("numpy", "numba")
        hf = numpy.heightfield
        assert np.mean(hf.heights[hf.inside] < hf.top) > 0.2     # much of the stock is cut
        np.testing.assert_array_max_ulp(numba.heightfield.heights, hf.heights, maxulp=1)
        assert numba.removed_volume_mm3 == pytest.approx(numpy.removed_volume_mm3, rel=1e-6)
        assert [(f.kind, f.operation, f.move) for f in numba.findings] == \
            [(f.kind, f.operation, f.move) for f in numpy.findings]
        assert [f.depth_mm for f in numba.findings] == pytest.approx([f.depth_mm for f in numpy.findings], abs=1e-6)
        kinds.append({f.kind for f in numpy.findings})
    assert kinds == [{"gouge", "rapid_in_material", "plunge"}, {"gouge", "plunge"}]


def test_kernel_choice(monkeypatch):
    with pytest.raises(ValueError, match="kernel"):
        sim.simulate(slot(FLAT6, 2.0), BOX, kernel="fortran")
    monkeypatch.setenv("KEZURI_NO_NUMBA", "1")
    assert sim.simulate(slot(FLAT6, 2.0), BOX, cell=0.5).kernel == "numpy"
    with pytest.raises(ValueError, match="KEZURI_NO_NUMBA"):
        sim.simulate(slot(FLAT6, 2.0), BOX, kernel="numba")


# ----- bad input ------------------------------------------------------------------------------------

def test_bad_arguments_are_refused_with_a_clear_message():
    op = slot(FLAT6, 2.0)
    with pytest.raises(ValueError, match="no moves"):
        sim.simulate(Program("empty", []), BOX)
    with pytest.raises(ValueError, match="cell"):
        sim.simulate(op, BOX, cell=0)
    with pytest.raises(ValueError, match="cell"):
        sim.simulate(op, BOX, cell=float("nan"))
    with pytest.raises(ValueError, match="encloses no volume"):
        sim.simulate(op, (0, 0, 0, 40, 40, 0))
    with pytest.raises(ValueError, match="positive"):
        sim.simulate(op, sim.CylinderStock(radius=-1, height=5))
    with pytest.raises(ValueError, match="engine"):
        sim.simulate(op, BOX, engine="voxels")
    with pytest.raises(ValueError, match="travel"):
        sim.simulate(op, BOX, travel={"q": (0, 1)})
    broken = slot(FLAT6, 2.0)
    broken.xyz[1, 0] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        sim.simulate(broken, BOX)
    with pytest.raises(ValueError, match="rotary"):
        sim.simulate(operation(FLAT6, [[0, 0, 0.0]], start=[0, 0, 5.0]).replace(rotary={"a": np.zeros(1)}), BOX)


def test_each_cell_knows_the_operation_whose_surface_shows_there(kernel):
    """Roughing cuts a slot along y = 20; finishing recuts its left half 1 mm deeper.  The right
    half shows the roughing, the left half the finishing, the rest of the stock was never cut."""
    roughing = operation(FLAT6, [[30.0, 20.0, -2.0]], [10.0, 20.0, -2.0], name="roughing")
    finishing = operation(FLAT6, [[20.0, 20.0, -3.0]], [10.0, 20.0, -3.0], name="finishing")
    hf = sim.simulate([roughing, finishing], BOX, cell=0.25, kernel=kernel).heightfield
    assert hf.operation.shape == hf.shape
    assert list(hf.operation_at([[26.0, 20.0], [14.0, 20.0], [5.0, 5.0], [35.0, 35.0]])) == [0, 1, -1, -1]
    assert set(np.unique(hf.operation)) == {-1, 0, 1}


@pytest.mark.parametrize("scale", [1.0, 1.0 - 1e-12, 1.0 + 1e-12, 1.0 + 1e-5, 1.0 + 1e-4, 1.001, 0.9, 1.1])
def test_a_v_bit_falling_along_its_own_flank_cuts_no_deeper_than_its_tip(scale):
    """A 60 deg V-bit fed down at exactly its flank's slope (2 mm over 2 tan 30 deg of XY) once cut
    the height field 12 mm deep beside a 2 mm move (the cone band's a/g blew up in rounding).
    Brute force: every cell's height is the lowest of the cone stamped at 2,001 places along the
    move (z + dist / tan 30 deg), within the stamping's spacing."""
    k = 1 / math.tan(math.radians(30))
    length = 2 / k * scale
    start = np.array([3.87, 3.87, 0.0])
    end = start + np.array([1, 1, 0]) / math.sqrt(2) * length
    end[2] = -2.0
    op = Operation("flank", Tool(1, "vbit", 12.0, tip_angle=60.0), 10000, np.array([RAPID, FEED]),
                   np.array([start, end]), np.array([np.nan, 300.0]), start=np.array([3.87, 3.87, 5.0]),
                   clearance_z=5.0, safe_z=5.0)
    hf = sim.simulate([op], sim.BoxStock(0, 0, -20, 12, 12, 0), cell=0.1).heightfield
    t = np.linspace(0, 1, 2001)
    places = start + t[:, None] * (end - start)
    x, y = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    lowest = np.full(x.shape, np.inf)
    for px, py, pz in places:
        lowest = np.minimum(lowest, pz + k * np.hypot(x - px, y - py))
    expected = np.minimum(lowest, 0.0)
    assert hf.heights.min() >= -2.0 - 1e-4
    assert np.abs(hf.heights - expected).max() <= k * length / 2000 + 1e-3
