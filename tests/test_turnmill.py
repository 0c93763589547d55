"""W4 turn-mill: direction classification, radial and axial paths, X-Z-C and CL data posts.

Analytic parts are built with manifold3d booleans (bar minus boxes and cylinders), so each face
can be told by its normal and position.  One module-wide plan of the built-in sample serves the
path and post tests.
"""
import re

import numpy as np
import pytest
import trimesh
from manifold3d import Manifold

import rs274
from kezuri.post import cldata, turnmill_xzc
from kezuri.post.gcode import PostError
from kezuri.toolpath.operations.turnmill import turnmill as tm
from kezuri.toolpath.engines.meshdata import MeshInputError
from kezuri.toolpath.ir import kinematics
from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Program, ProgramError, Tool

needs_rs274 = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")

R = 3.0      # the 6 mm ball
TOL = 0.01


def mesh_of(solid):
    mesh = solid.to_mesh64()
    return np.array(mesh.vert_properties[:, :3], dtype=float), np.array(mesh.tri_verts, dtype=np.int64)


def bar(radius=20.0, length=30.0, segments=48):
    """A bar on the Z axis, end face at z = 0."""
    return Manifold.cylinder(length, radius, radius, segments).translate((0.0, 0.0, -length))


def face_info(v, f):
    tri = v[f]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    return normal, tri.mean(axis=1)


def surface_distance(v, f, points):
    """Brute-force distance from each point to the mesh (trimesh's pairwise closest point)."""
    triangles = v[f]
    out = []
    for p in points:
        closest = trimesh.triangles.closest_point(triangles, np.repeat(p[None], len(triangles), axis=0))
        out.append(np.linalg.norm(closest - p, axis=1).min())
    return np.array(out)


# ----- classification ----------------------------------------------------------------------------
def test_plain_cylinder_side_radial_top_axial_bottom_neither():
    v, f = mesh_of(bar())
    labels = tm.classify_faces(v, f)
    normal, _ = face_info(v, f)
    top, bottom = normal[:, 2] > 0.99, normal[:, 2] < -0.99
    side = ~top & ~bottom
    assert np.all(labels[side] == tm.RADIAL)
    assert np.all(labels[top] == tm.AXIAL)
    assert np.all(labels[bottom] == tm.NEITHER)


def side_pocket(open_top=False, wedge=True):
    """A pocket in the side of a 40 mm bar: floor x = 15, z -20..-10 (or open to the end face).
    With ``wedge`` its side walls are radial planes at +/-25 degrees; without, it is a flat
    across the whole bar with shoulders only."""
    top = 1.0 if open_top else -10.0
    cut = Manifold.cube((20.0, 60.0, top + 20.0)).translate((15.0, -30.0, -20.0))
    if wedge:
        half = Manifold.cube((100.0, 100.0, 100.0)).translate((-50.0, -100.0, -50.0))
        cut = cut ^ half.rotate((0.0, 0.0, 25.0)) ^ half.rotate((180.0, 0.0, -25.0))
    return mesh_of(bar() - cut)


def test_side_pocket_floor_radial_walls_and_shoulders_neither():
    v, f = side_pocket()
    labels = tm.classify_faces(v, f)
    normal, centre = face_info(v, f)
    in_pocket = (centre[:, 2] > -20.01) & (centre[:, 2] < -9.99) & (np.hypot(centre[:, 0], centre[:, 1]) < 19.9)
    floor = in_pocket & (normal[:, 0] > 0.999)
    shoulders = in_pocket & (np.abs(normal[:, 2]) > 0.999)
    walls = in_pocket & ~floor & ~shoulders
    assert floor.sum() >= 2 and shoulders.sum() >= 2 and walls.sum() >= 2
    assert np.all(labels[floor] == tm.RADIAL)
    # The lower shoulder faces +Z but the upper one hangs over it; the upper one faces down.
    assert np.all(labels[shoulders] == tm.NEITHER)
    # The wedge walls are radial planes: they face neither the radial direction nor +Z.
    assert np.all(labels[walls] == tm.NEITHER)


def test_an_overhang_shadows_the_shoulder_below_it():
    for open_top, expected in ((False, tm.NEITHER), (True, tm.AXIAL)):
        v, f = side_pocket(open_top=open_top, wedge=False)
        labels = tm.classify_faces(v, f)
        normal, centre = face_info(v, f)
        lower_shoulder = (normal[:, 2] > 0.999) & (np.abs(centre[:, 2] + 20.0) < 1e-6)
        assert lower_shoulder.any()
        assert np.all(labels[lower_shoulder] == expected), open_top


def test_deep_hole_floor_axial_walls_neither():
    hole = Manifold.cylinder(21.0, 4.0, 4.0, 32).translate((8.0, 0.0, -20.0))
    v, f = mesh_of(bar() - hole)
    labels = tm.classify_faces(v, f)
    normal, centre = face_info(v, f)
    in_hole = np.hypot(centre[:, 0] - 8.0, centre[:, 1]) < 4.01
    floor = in_hole & (np.abs(centre[:, 2] + 20.0) < 1e-6)
    walls = in_hole & (np.abs(normal[:, 2]) < 1e-6)
    assert floor.any() and walls.any()
    assert np.all(labels[floor] == tm.AXIAL)
    # The half of the wall facing away from the axis faces radially, but its rays hit the far wall.
    faces_out = walls & (np.einsum("ij,ij->i", normal[:, :2], centre[:, :2]) > 0)
    assert faces_out.any()
    assert np.all(labels[walls] == tm.NEITHER)


def test_chunked_rays_give_the_same_labels_and_any_engine_can_be_plugged_in():
    v, f = side_pocket()
    whole = tm.classify_faces(v, f, engine=tm.TrimeshRayEngine(v, f, chunk_size=10 ** 9))

    class Counting:
        """Another engine with the same method, as the Blender shell's BVH engine."""

        def __init__(self):
            self.inner = tm.TrimeshRayEngine(v, f, chunk_size=37)
            self.rays = 0

        def intersects_any(self, origins, directions):
            self.rays += len(origins)
            return self.inner.intersects_any(origins, directions)

    engine = Counting()
    assert np.array_equal(tm.classify_faces(v, f, engine=engine), whole)
    assert engine.rays > 37
    assert tm.TrimeshRayEngine(v, f).backend in ("embree", "numpy")


def test_face_samples_are_deterministic_and_area_weighted():
    tri = np.array([[[0, 0, 0], [10, 0, 0], [0, 10, 0]], [[0, 0, 0], [1, 0, 0], [0, 1, 0]]], dtype=float)
    points, owner = tm.face_samples(tri, 2.0)
    again, _ = tm.face_samples(tri, 2.0)
    assert np.array_equal(points, again)
    counts = np.bincount(owner)
    assert counts[1] == 4 and counts[0] > counts[1]          # several per face, more on the big one
    assert np.allclose(points[owner == 0].mean(axis=0), tri[0].mean(axis=0))


def test_bad_input_is_rejected_with_clear_errors():
    v, f = mesh_of(bar())
    with pytest.raises(MeshInputError, match="empty"):
        tm.classify_faces(np.empty((0, 3)), np.empty((0, 3), dtype=int))
    bad = v.copy()
    bad[3, 1] = np.nan
    with pytest.raises(MeshInputError, match="NaN"):
        tm.classify_faces(bad, f)
    with pytest.raises(MeshInputError, match="non-manifold"):
        tm.check_mesh(np.vstack([v, [[0, 0, 50]]]), np.vstack([f, [[f[0, 0], f[0, 1], len(v)]]]))
    with pytest.raises(MeshInputError, match="inward"):
        tm.check_mesh(v, f[:, ::-1])
    flipped = f.copy()
    flipped[0] = flipped[0, ::-1]
    with pytest.raises(MeshInputError, match="inconsistently"):
        tm.check_mesh(v, flipped)
    with pytest.raises(tm.TurnMillError, match="tool radius"):
        tm.TurnMillSettings(tool_diameter=0.0)
    with pytest.raises(tm.TurnMillError, match="tool radius"):
        tm.TurnMillSettings(tool_diameter=-6.0)
    with pytest.raises(tm.TurnMillError, match="tolerance"):
        tm.TurnMillSettings(tolerance=0.0)
    with pytest.raises(tm.TurnMillError, match="stock"):
        tm.Stock(radius=20.0, z_min=0.0, z_max=-30.0)
    with pytest.raises(tm.TurnMillError, match="does not fit"):
        tm.plan(v, f, tm.Stock(radius=19.0, z_min=-30.0, z_max=0.0))

    class Broken:
        def intersects_any(self, origins, directions):
            return np.zeros(3, dtype=bool)

    with pytest.raises(tm.TurnMillError, match="ray engine"):
        tm.classify_faces(v, f, engine=Broken())
    assert issubclass(tm.TurnMillError, ValueError)


def test_chaining_follows_the_papers_order():
    # outward (+i), counter-clockwise (+j), inward, clockwise: a 3 x 3 grid is one path that
    # goes out, around counter-clockwise, and in to the middle.
    paths = tm.chain_cells(np.ones((3, 3), dtype=bool))
    assert paths == [[(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (1, 2), (0, 2), (0, 1), (1, 1)]]
    occupied = np.zeros((4, 4), dtype=bool)
    occupied[:2, :2] = occupied[3, 3] = True
    assert [len(p) for p in tm.chain_cells(occupied)] == [4, 1]


def test_default_stepover_leaves_a_scallop_of_the_tolerance():
    settings = tm.TurnMillSettings()
    s = settings.pick_feed
    assert R - np.sqrt(R * R - (s / 2) ** 2) == pytest.approx(TOL, rel=1e-9)
    assert settings.max_turn < np.radians(10)


# ----- the sample: paths ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def sample():
    v, f, stock = tm.sample_part()
    return v, f, stock, tm.plan(v, f, stock, name="sample")


def ops_by_name(plan):
    return {op.name: op for op in plan.program.operations}


def test_sample_has_both_tools_on_separate_stations(sample):
    *_, plan = sample
    ops = ops_by_name(plan)
    assert list(ops) == ["radial roughing", "radial finishing", "axial roughing", "axial finishing"]
    assert {ops["radial finishing"].tool.number, ops["axial finishing"].tool.number} == {1, 2}
    assert ops["radial roughing"].direction == "radial" and ops["axial roughing"].direction == "axial"
    for op in ops.values():
        assert op.tool.kind == "ball" and op.tool.diameter == 6.0
        assert np.all(op.xyz[:, 1] == 0.0)
    counts = np.bincount(plan.labels, minlength=4)
    assert counts[tm.RADIAL] and counts[tm.AXIAL] and counts[tm.NEITHER]


def test_radial_centres_sit_one_tool_radius_off_the_surface_inside_the_stock(sample):
    v, f, stock, plan = sample
    finishing = np.vstack(plan.radial_layers[-1])
    every = np.vstack([p for layer in plan.radial_layers for p in layer])
    # Both the flat (x = 35 -> centres at 38) and the groove floor (radius 36 -> 39) are cut.
    rho = np.hypot(finishing[:, 0], finishing[:, 1])
    assert np.any(np.abs(rho - 39.0) < 1e-3) and np.any(np.abs(finishing[:, 0] - 38.0) < 1e-3)
    pick = np.linspace(0, len(finishing) - 1, 120).astype(int)
    assert np.allclose(surface_distance(v, f, finishing[pick]), R, atol=TOL)
    pick = np.linspace(0, len(every) - 1, 120).astype(int)
    assert np.all(surface_distance(v, f, every[pick]) >= R - TOL)
    assert np.all(stock.distance(every) < R - TOL)           # every centre cuts stock
    # The groove floor (z -20..-12) and the flat (z -45..-30) are cut to their full height: the
    # centres over them reach exactly a tool radius from the shoulders.
    over_flat = (np.abs(finishing[:, 0] - 38.0) < 1e-3) & (np.abs(finishing[:, 1]) < 15.0)
    for over, low, high in ((np.abs(rho - 39.0) < 1e-3, -17.0, -15.0), (over_flat, -42.0, -33.0)):
        z = finishing[over, 2]
        assert z.min() == pytest.approx(low, abs=1e-6) and z.max() == pytest.approx(high, abs=1e-6)


def test_axial_slot_is_twenty_millimetres_wide(sample):
    *_, plan = sample
    centres = np.vstack(plan.axial_layers[-1])
    slot = centres[(centres[:, 0] > 0) & (np.abs(centres[:, 2] + 3.0) < 1e-6)]
    assert slot[:, 0].max() - slot[:, 0].min() + 2 * R == pytest.approx(20.0, abs=0.01)
    assert slot[:, 1].max() - slot[:, 1].min() + 2 * R == pytest.approx(30.0, abs=0.01)
    # The operation's ball centres say the same.
    op = ops_by_name(plan)["axial finishing"]
    ball = op.ball_centres()[op.kind == FEED]
    ball = ball[(ball[:, 0] > 0) & (np.abs(ball[:, 2] + 3.0) < 1e-6)]
    assert ball[:, 0].max() - ball[:, 0].min() + 2 * R == pytest.approx(20.0, abs=0.01)


def test_slot_width_does_not_depend_on_the_point_spacing(sample):
    # The paper's 19.8 mm came from coarse points; pushed ball centres end on the walls anyway.
    v, f, stock, plan = sample
    coarse = tm.TurnMillSettings(stepover=2.5)
    layers = tm.axial_layers(v, f, plan.axial_faces, stock, coarse)
    centres = np.vstack(layers[-1])
    slot = centres[(centres[:, 0] > 0) & (np.abs(centres[:, 2] + 3.0) < 1e-6)]
    assert slot[:, 0].max() - slot[:, 0].min() + 2 * R == pytest.approx(20.0, abs=0.01)


def test_axial_roughing_copies_rise_until_they_clear_the_stock(sample):
    *_, stock, plan = sample
    tops = [min(p[:, 2].min() for p in layer) for layer in plan.axial_layers]
    assert tops == sorted(tops, reverse=True)                 # executed from the top down
    assert tops[0] < stock.z_max + R - TOL                    # the highest copy still cuts
    slot_floor = -3.0
    assert tops[-1] == pytest.approx(slot_floor)


def test_c_is_continuous_and_polar_interpolation_stays_within_tolerance(sample):
    *_, plan = sample
    for op in plan.program.operations:
        c = op.rotary["c"]
        assert np.all(np.abs(np.diff(c)) < 180.0), op.name
        # Linear X-Z-C interpolation: the middle of every cutting move against the part chord.
        start = np.vstack([op.start, op.xyz[:-1]])
        c_start = np.r_[c[0], c[:-1]]
        cutting = op.kind == FEED
        a = kinematics.machine_to_part(start[cutting], c_start[cutting])
        b = kinematics.machine_to_part(op.xyz[cutting], c[cutting])
        middle = kinematics.machine_to_part(0.5 * (start[cutting] + op.xyz[cutting]), 0.5 * (c_start[cutting] + c[cutting]))
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", middle - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        off = np.linalg.norm(middle - (a + t[:, None] * ab), axis=1)
        assert off.max() <= TOL * 1.001, op.name


def test_c_sign_convention(sample):
    # The slot lies on +X (C near 0), the round pocket at (-20, 0) (C near 180).
    *_, plan = sample
    op = ops_by_name(plan)["axial finishing"]
    centres = op.ball_centres()
    c = np.mod(op.rotary["c"] + 180.0, 360.0) - 180.0
    slot = (op.kind == FEED) & (centres[:, 0] > 0)
    pocket = (op.kind == FEED) & (centres[:, 0] < 0)
    assert np.all(np.abs(c[slot]) < 45.0) and np.all(np.abs(c[pocket]) > 135.0)
    # X is the tip's radius; rotating the part by -C brings the point onto +X.
    tips = op.part_points()
    angle = np.radians(op.rotary["c"])
    back = np.column_stack([np.cos(-angle) * tips[:, 0] - np.sin(-angle) * tips[:, 1],
                            np.sin(-angle) * tips[:, 0] + np.cos(-angle) * tips[:, 1]])
    assert np.allclose(back[:, 0], op.xyz[:, 0]) and np.allclose(back[:, 1], 0.0, atol=1e-9)


# ----- posts ---------------------------------------------------------------------------------------
def test_xzc_post_is_deterministic_with_machine_codes_and_diameter_x(sample):
    *_, plan = sample
    post = turnmill_xzc.TurnMillXZCPost()
    text = post.to_text(plan.program)
    assert text == turnmill_xzc.TurnMillXZCPost().to_text(plan.program)
    lines = text.splitlines()
    assert lines[0] == "%" and lines[1].startswith("O0001") and lines[-1] == "%"
    assert "(ESTIMATED CYCLE TIME:" in text and "(OPERATION: AXIAL FINISHING - T2 -" in text
    for code in ("T0101", "T0202", "M154", "M155", "M133 P4000", "M135", "G19", "G17", "G93", "G98", "M30"):
        assert code in lines, code
    assert not re.search(r"\bY-?\d", text)
    first = next(line for line in lines if line.startswith("G00 X"))
    op = plan.program.operations[0]
    assert float(re.search(r"X(-?[\d.]+)", first).group(1)) == pytest.approx(2 * op.start[0])
    custom = turnmill_xzc.TurnMillXZCPost(turnmill_xzc.TurnMillCodes(c_axis_on="M18", c_axis_off="M19"),
                                          x_diameter=False, inverse_time=False)
    other = custom.to_text(plan.program)
    assert "M18" in other and "M154" not in other and "G93" not in other and "F500." in other


def test_xzc_post_rejects_plain_milling_operations():
    op = Operation("plain", Tool(1, "ball", 6.0), 1000, [FEED], [[1, 2, 3]], [100.0], start=[0, 0, 10])
    with pytest.raises(PostError, match="turn-mill"):
        turnmill_xzc.TurnMillXZCPost().to_text(Program("p", [op]))
    with pytest.raises(ProgramError, match="Y axis"):
        tm.TurnMillOperation("y", Tool(1, "ball", 6.0), 1000, [FEED], [[1, 2, 3]], [100.0], rotary={"c": [0.0]})


@needs_rs274
def test_linuxcnc_variant_passes_rs274_and_matches_the_ir(sample):
    *_, plan = sample
    program = Program("finishing", [op for op in plan.program.operations if "finishing" in op.name])
    text = turnmill_xzc.TurnMillLinuxCNCPost().to_text(program)
    assert not re.search(r"\bM1\d\d\b|\bY-?\d", text)
    kinds, points, rotary = rs274.motion_endpoints(rs274.run(text))
    want, want_c = [], []
    for op in program.operations:
        last = np.round(np.r_[op.start[[0, 2]], op.rotary["c"][0]], 4)
        for kind, xyz, c in zip(op.kind, op.xyz, op.rotary["c"]):
            here = np.round([xyz[0], xyz[2], c], 4)
            if not np.array_equal(here, last) and kind == FEED:
                want.append(xyz)
                want_c.append(c)
            last = here
    feeds = [i for i, k in enumerate(kinds) if k == "feed"]
    assert len(feeds) == len(want)
    assert np.max(np.abs(points[feeds] - np.array(want))) < 1e-3
    assert np.max(np.abs(rotary[feeds, 2] - np.array(want_c))) < 1e-3


def test_cl_data_has_one_goto_per_move_in_part_coordinates(sample):
    *_, plan = sample
    text = cldata.CLDataPost().to_text(plan.program)
    lines = text.splitlines()
    assert lines[0] == "PARTNO/SAMPLE" and lines[-1] == "FINI"
    assert "UNITS/MM" in lines and "MULTAX/ON" in lines
    assert all(len(line) <= 72 for line in lines)
    assert all(re.fullmatch(r"\$\$ .*|[A-Z]+(/.*)?", line) for line in lines)
    assert lines.count("CUTTER/6.0000,3.0000") == 4 and "LOADTL/1" in lines and "LOADTL/2" in lines
    gotos = [line for line in lines if line.startswith("GOTO/")]
    assert len(gotos) == sum(len(op) for op in plan.program.operations)
    values = np.array([[float(x) for x in line[5:].split(",")] for line in gotos])
    assert values.shape[1] == 6
    assert np.allclose(np.linalg.norm(values[:, 3:], axis=1), 1.0, atol=1e-5)
    expected = np.vstack([op.part_points() for op in plan.program.operations])
    assert np.max(np.abs(values[:, :3] - expected)) < 1e-4 + 1e-12
    radial = sum(len(op) for op in plan.program.operations if op.direction == "radial")
    assert np.allclose(values[:radial, 5], 0.0) and np.allclose(values[radial:, 3:], [0.0, 0.0, 1.0])
    assert lines.count("RAPID") == sum(int(np.sum(op.kind == RAPID)) for op in plan.program.operations)


def test_cl_data_writes_plain_three_axis_operations_and_rejects_arcs():
    op = Operation("plain", Tool(3, "ball", 4.0), 1000, [RAPID, FEED], [[1, 2, 5], [1, 2, -1]], [np.nan, 80.0],
                   start=[0, 0, 10])
    text = cldata.CLDataPost().to_text(Program("plain", [op]))
    assert "GOTO/1.0000,2.0000,-1.0000,0.000000,0.000000,1.000000" in text.splitlines()
    assert "CUTTER/4.0000,2.0000" in text and "FEDRAT/MMPM,80.0" in text
    arc = Operation("arc", Tool(3, "ball", 4.0), 1000, [2], [[1, 0, 0]], [80.0], center=[[0, 0, 0]], start=[1, 0, 0])
    with pytest.raises(PostError, match="arc"):
        cldata.CLDataPost().to_text(Program("arc", [arc]))
