"""W3: ISO 14649 (STEP-NC) workplans to G-code (toolpath/operations/stepnc/model.py and workplan.py).

The reference is ISO 14649-11 Example 1 as NIST runs it (fixtures/iso14649/ex1.stp) and
NIST's interpreter output for it (ex1.can): a planar face, a drilled and reamed hole, and a
closed pocket (80 x 50, R10 corners, 30 deep) roughed and finished with an 18 mm end mill.
"""
import functools
import math
import os
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Tool
from kezuri.toolpath.operations.stepnc.errors import StepNcError
from kezuri.toolpath.operations.stepnc.features import ClosedPocket, GeneralClosedProfile, PlanarFace, RectangularClosedProfile, RoundHole
from kezuri.toolpath.operations.stepnc.process import Bidirectional, BottomAndSideMilling, ContourParallel, PlaneMilling
from kezuri.toolpath.operations.stepnc.part21 import Part21Error
from kezuri.toolpath.operations.stepnc.workplan import (PocketSpec, finishing_leftover, load_workplan, pocket_region, pockets_to_part21, to_program)

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = os.path.join(FIXTURES, "iso14649", "ex1.stp")
EX1_CAN = os.path.join(FIXTURES, "iso14649", "ex1.can")

needs_rs274 = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")

# ex1: the pocket is centred at (70, 70), 80 long along Y (its ref_direction) and 50 wide, R10 corners.
POCKET_CENTRE, POCKET_HALF, POCKET_RADIUS = np.array([70.0, 70.0]), np.array([25.0, 40.0]), 10.0
MILL_RADIUS = 9.0


# --------------------------------------------------------------------------- helpers


def ex1_text() -> str:
    with open(EX1) as stream:
        return stream.read()


def replace_instance(text: str, ident: int, new: str) -> str:
    """Replace the live line(s) of instance #ident (not the commented-out versions)."""
    pattern = re.compile(rf"^#{ident}=.*?;[ \t]*$", re.MULTILINE | re.DOTALL)
    assert len(pattern.findall(text)) == 1, f"#{ident} not found once"
    return pattern.sub(lambda _: new, text)


def add_instances(text: str, *lines: str) -> str:
    head, _, tail = text.rpartition("ENDSEC;")
    return head + "\n".join(lines) + "\nENDSEC;" + tail


def rounded_rect_wall_distance(points, centre=POCKET_CENTRE, half=POCKET_HALF, radius=POCKET_RADIUS):
    """Distance from points inside a rounded rectangle to its wall (analytic, not our polygons)."""
    q = np.abs(np.asarray(points)[:, :2] - centre) - (half - radius)
    outside = np.linalg.norm(np.maximum(q, 0.0), axis=1)
    inside = np.minimum(np.maximum(q[:, 0], q[:, 1]), 0.0)
    return -(outside + inside - radius)


def segment_distance(points, a, b):
    """Distance from points to the nearest of the segments a[i]-b[i] (XY)."""
    p = np.asarray(points)[:, None, :2]
    a, b = np.asarray(a, float)[None, :, :2], np.asarray(b, float)[None, :, :2]
    t = np.clip(np.sum((p - a) * (b - a), axis=2) / np.maximum(np.sum((b - a) ** 2, axis=2), 1e-30), 0, 1)
    return np.min(np.linalg.norm(p - (a + t[..., None] * (b - a)), axis=2), axis=1)


def polygon_wall_distance(points, polygon):
    """Distance from points to the nearest edge of a polygon."""
    return segment_distance(points, polygon, np.roll(np.asarray(polygon, float), -1, axis=0))


def cut_points(op, densify=True):
    """End points (and midpoints) of the straight cutting moves that travel in XY at one height."""
    a, b = op.start_points(), op.xyz
    flat = (op.kind == FEED) & (np.abs(a[:, 2] - b[:, 2]) < 1e-9) & (np.linalg.norm(b[:, :2] - a[:, :2], axis=1) > 1e-9)
    points = [b[flat]] + ([(a[flat] + b[flat]) / 2] if densify else [])
    return np.vstack(points)


def xy_levels(op):
    return sorted({round(z, 4) for z in cut_points(op, densify=False)[:, 2]})


def expected_cutting_endpoints(program, decimals=4):
    """The IR's cutting moves in order, dropping the ones that round to zero length (as the post does)."""
    points, kinds = [], []
    for op in program.operations:
        last = np.round(op.start, decimals)
        for kind, xyz in zip(op.kind, op.xyz):
            p = np.round(xyz, decimals)
            if np.array_equal(p, last) and kind in (RAPID, FEED):
                continue
            last = p
            if kind != RAPID:
                points.append(xyz)
                kinds.append({FEED: "feed", ARC_CW: "cw", ARC_CCW: "ccw"}[int(kind)])
    return kinds, np.array(points)


def nist_segments():
    """ex1.can split at each CHANGE_TOOL: [(tool name, [(call, args)])]."""
    segments = []
    with open(EX1_CAN) as stream:
        for line in stream:
            match = re.match(r"\s*\d+\s+([A-Z_]+)\((.*)\)\s*$", line)
            if not match:
                continue
            name, args = match.group(1), match.group(2)
            if name == "CHANGE_TOOL":
                segments.append((args, []))
            elif segments:
                segments[-1][1].append((name, args.split(",")))
    return segments


def nist_xy_levels(calls, start_z=200.0):
    """{z: (xmin, xmax, ymin, ymax)} of the feeds (lines and arcs) that travel in XY at one height."""
    levels = {}
    x = y = math.nan
    z = start_z
    for name, args in calls:
        if name not in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
            continue
        values = [float(v) for v in args]
        nx, ny, nz = (values[0], values[1], values[2]) if name != "ARC_FEED" else (values[0], values[1], values[5])
        if name != "STRAIGHT_TRAVERSE" and abs(nz - z) < 1e-9 and (nx, ny) != (x, y):
            box = levels.get(round(nz, 4), (math.inf, -math.inf, math.inf, -math.inf))
            levels[round(nz, 4)] = (min(box[0], x, nx), max(box[1], x, nx), min(box[2], y, ny), max(box[3], y, ny))
        x, y, z = nx, ny, nz
    return levels


def our_xy_levels(*ops):
    levels = {}
    for op in ops:
        points = cut_points(op)
        starts = op.start_points()
        for z in xy_levels(op):
            at = np.vstack([points[np.abs(points[:, 2] - z) < 1e-4],
                            starts[(np.abs(starts[:, 2] - z) < 1e-4) & (op.kind == FEED)]])
            box = levels.get(z, (math.inf, -math.inf, math.inf, -math.inf))
            levels[z] = (min(box[0], at[:, 0].min()), max(box[1], at[:, 0].max()),
                         min(box[2], at[:, 1].min()), max(box[3], at[:, 1].max()))
    return levels


@pytest.fixture(scope="module")
def ex1():
    return load_workplan(EX1)


@pytest.fixture(scope="module")
def ex1_program(ex1):
    return to_program(ex1)


def by_name(program):
    return {op.name: op for op in program.operations}


TWO_POCKETS = [
    PocketSpec("POCKET 1", ((10.0, 10.0), (40.0, 10.0), (40.0, 30.0), (10.0, 30.0)), 5.0, corner_radius=3.0),
    PocketSpec("POCKET 2", ((50.0, 10.0), (90.0, 10.0), (90.0, 25.0), (65.0, 25.0), (65.0, 50.0), (50.0, 50.0)), 4.0),
]
STOCK = ((0.0, 0.0, -20.0), (100.0, 60.0, 0.0))
FLAT_4 = Tool(1, "flat", 4.0, flute_length=15.0, name="FLAT 4MM")  # the paper's 4 mm flat end mill


@pytest.fixture(scope="module")
def two_pockets():
    text = pockets_to_part21(STOCK, TWO_POCKETS, FLAT_4, feed=600.0, spindle_rpm=12000.0, axial_depth=2.0,
                             allowance_side=0.5, allowance_bottom=0.2, overlap=0.5)
    return text, load_workplan(text)


# --------------------------------------------------------------------------- ex1: the model


def test_ex1_has_five_workingsteps_in_workplan_order(ex1):
    assert [ws.id for ws in ex1.workingsteps] == [10, 11, 12, 13, 14]
    assert [ws.its_id for ws in ex1.workingsteps] == [
        "WS FINISH PLANAR FACE1", "WS DRILL HOLE1", "WS REAM HOLE1", "WS ROUGH POCKET1", "WS FINISH POCKET1"]
    assert ex1.warnings == ()
    face, drill, ream, rough, finish = ex1.workingsteps
    assert isinstance(face.its_feature, PlanarFace) and isinstance(face.its_operation, PlaneMilling)
    assert isinstance(drill.its_feature, RoundHole) and drill.its_operation.type_name == "DRILLING"
    assert ream.its_operation.type_name == "REAMING" and ream.its_operation.spindle_stop_at_bottom is True
    assert rough.its_feature is finish.its_feature and isinstance(rough.its_feature, ClosedPocket)
    assert isinstance(rough.its_operation, BottomAndSideMilling) and not rough.its_operation.finishing
    assert finish.its_operation.finishing
    assert face.its_secplane.position.location == (0.0, 0.0, 30.0)


def test_ex1_features(ex1):
    face, drill, _, rough, finish = ex1.workingsteps
    assert face.its_feature.top_z == 5.0 and face.its_feature.bottom_z == 0.0
    np.testing.assert_allclose(face.its_feature.corners(), [[0, 0], [0, 120], [100, 120], [100, 0]])
    hole = drill.its_feature
    assert hole.centre == (20.0, 60.0) and hole.bottom_z == -30.0 and hole.diameter == 22.0
    assert hole.bottom_condition == "THROUGH_BOTTOM_CONDITION"
    pocket = rough.its_feature
    assert isinstance(pocket.feature_boundary, RectangularClosedProfile)
    assert (pocket.feature_boundary.profile_width, pocket.feature_boundary.profile_length) == (50.0, 80.0)
    assert pocket.orthogonal_radius == 10.0 and pocket.top_z == 0.0 and pocket.bottom_z == -30.0
    # length along the placement's ref_direction (0, 1, 0): X 45..95, Y 30..110
    outline = pocket.outline()
    assert outline.min(axis=0) == pytest.approx([45, 30]) and outline.max(axis=0) == pytest.approx([95, 110])
    area = 80 * 50 - (4 - math.pi) * POCKET_RADIUS ** 2
    assert pocket_region(pocket).area() == pytest.approx(area, abs=0.05)
    op = rough.its_operation
    depths = (op.axial_cutting_depth, op.radial_cutting_depth, op.allowance_side, op.allowance_bottom)
    assert depths == (6.5, 5.0, 1.0, 0.5)
    assert isinstance(op.its_machining_strategy, ContourParallel)
    assert op.its_machining_strategy.rotation_direction == "CW"
    strategy = face.its_operation.its_machining_strategy
    assert isinstance(strategy, Bidirectional)
    assert strategy.overlap == 0.05 and strategy.feed_direction == (0.0, 1.0, 0.0)
    assert strategy.stepover_direction == "LEFT" and strategy.allow_multiple_passes is True


def test_ex1_tools_and_technology_converted(ex1, ex1_program):
    technology = ex1.workingsteps[0].its_operation.its_technology
    assert technology.feed_mm_min == pytest.approx(2400.0)   # 0.04 m/s
    assert technology.spindle_rpm == pytest.approx(720.0)    # -12 rev/s
    assert technology.spindle_clockwise
    ops = ex1_program.operations
    assert [op.name for op in ops] == [ws.its_id for ws in ex1.workingsteps]
    assert [op.tool.number for op in ops] == [1, 2, 3, 1, 1]
    mill, drill, reamer = ops[0].tool, ops[1].tool, ops[2].tool
    assert (mill.name, mill.kind, mill.diameter, mill.flute_length) == ("MILL 18MM", "flat", 18.0, 29.0)
    assert (drill.name, drill.kind, drill.diameter) == ("SPIRAL_DRILL_20MM", "drill", 20.0)
    assert (reamer.name, reamer.kind, reamer.diameter) == ("REAMER_22MM", "drill", 22.0)
    # NIST: SET_SPINDLE_SPEED 720 (face), 960 (drill), 1080 (ream), 1200 (pocket); all clockwise
    assert [op.spindle_rpm for op in ops] == pytest.approx([720, 960, 1080, 1200, 1200])
    assert all(op.spindle_cw for op in ops)
    assert {float(f) for f in ops[0].feed[ops[0].kind == FEED]} == {2400.0}
    assert all(op.safe_z == 30.0 for op in ops)           # the security plane
    assert [op.clearance_z for op in ops] == [15.0, 10.0, 10.0, 15.0, 15.0]  # feature top + retract_plane
    assert ops[0].coolant  # MILLING_MACHINE_FUNCTIONS coolant .T.
    # what G-code without canned cycles cannot say is reported, not dropped silently
    assert any("#11" in note and "reduced spindle" in note for note in ex1_program.notes)
    assert any("#12" in note and "spindle is not stopped" in note for note in ex1_program.notes)


# --------------------------------------------------------------------------- ex1: motion


def test_planar_face_passes_at_2_5_and_0_within_the_face(ex1_program):
    face = ex1_program.operations[0]
    assert xy_levels(face) == [0.0, 2.5]     # face depth 5 in axial steps of 2.5, as in ex1.can
    points = cut_points(face)
    # strokes run along Y (the feed direction) past both ends, stepping over in X
    assert points[:, 1].min() == pytest.approx(-MILL_RADIUS - 2.0) and points[:, 1].max() == pytest.approx(129 + 2.0)
    xs = np.unique(np.round(points[np.abs(points[:, 1] - 131.0) < 1e-9, 0], 6))
    assert xs.min() >= 0 + MILL_RADIUS - 0.9 - 1e-9 and xs.max() <= 100 - MILL_RADIUS + 0.9 + 1e-9
    # the tool covers the whole face width, stepover at most d (1 - overlap) = 17.1
    assert xs.min() - MILL_RADIUS <= 0 and xs.max() + MILL_RADIUS >= 100
    assert np.diff(np.sort(xs)).max() <= 17.1 + 1e-9
    # the first stroke is on the right and the steps go left of the feed direction (+Y): -X
    first = face.xyz[face.kind == FEED][0]
    assert first[0] == pytest.approx(xs.max())


def test_pocket_roughing_stays_inside_the_allowance(ex1_program):
    rough = by_name(ex1_program)["WS ROUGH POCKET1"]
    points = cut_points(rough)
    wall = rounded_rect_wall_distance(points)
    assert wall.min() >= MILL_RADIUS + 1.0 - 1e-6              # tool radius + allowance_side
    assert wall.min() == pytest.approx(MILL_RADIUS + 1.0, abs=1e-6)
    assert rough.xyz[:, 2].min() == pytest.approx(-30 + 0.5)   # depth + allowance_bottom
    assert xy_levels(rough) == pytest.approx([-29.5, -23.6, -17.7, -11.8, -5.9])  # 29.5 in 5 layers <= 6.5


def test_pocket_finishing_cuts_the_walls_and_the_floor(ex1_program):
    finish = by_name(ex1_program)["WS FINISH POCKET1"]
    assert xy_levels(finish) == pytest.approx([-2.0 * k for k in range(15, 0, -1)])  # axial depth 2 to -30
    points = cut_points(finish)
    walls = points[points[:, 2] > -29.5 + 1e-9]
    # above the rough floor it cuts only what roughing left: the tool edge on the wall
    distance = rounded_rect_wall_distance(walls)
    assert np.abs(distance - MILL_RADIUS).max() <= 0.01
    floor = points[np.abs(points[:, 2] + 30) < 1e-9]
    assert rounded_rect_wall_distance(floor).min() == pytest.approx(MILL_RADIUS, abs=0.01)
    # at full depth the whole floor is cut: every point of the pocket within the tool radius of the path
    a, b = finish.start_points(), finish.xyz
    at_floor = (finish.kind == FEED) & (np.abs(a[:, 2] + 30) < 1e-9) & (np.abs(b[:, 2] + 30) < 1e-9)
    grid = np.stack(np.meshgrid(np.linspace(45, 95, 51), np.linspace(30, 110, 81)), axis=-1).reshape(-1, 2)
    grid = grid[rounded_rect_wall_distance(grid) >= 0]
    assert segment_distance(grid, a[at_floor], b[at_floor]).max() <= MILL_RADIUS + 0.01


# ex1's HOLE1 is a through hole (#17 bottom condition #26 THROUGH_BOTTOM_CONDITION) whose depth plane #112
# is at Z -30.  Its drill #31/#32 is 20 mm with tool_top_angle 31 degrees, the cutting edge's angle to
# the plane square to the axis (the usual 118 degree point: 2 x (90 - 31)), so the point is
# 10 x tan 31 deg = 6.0086 mm long.  Drilled through: the tip goes the point's length plus 2 mm below
# Z -30, so the full 20 mm diameter is 2 mm past the bottom.
EX1_DRILL_POINT = 10.0 * math.tan(math.radians(31.0))
EX1_DRILL_BOTTOM = -30.0 - EX1_DRILL_POINT - 2.0          # -38.0086


def test_hole_drilled_through_and_reamed_at_its_centre(ex1_program):
    drill, ream = by_name(ex1_program)["WS DRILL HOLE1"], by_name(ex1_program)["WS REAM HOLE1"]
    assert EX1_DRILL_POINT == pytest.approx(6.0086, abs=1e-4)
    for op in (drill, ream):
        cutting = op.kind == FEED
        np.testing.assert_allclose(op.xyz[cutting, :2], [[20.0, 60.0]] * int(cutting.sum()))
        assert np.all(op.xyz[:, :2] == [20.0, 60.0])
    assert drill.xyz[:, 2].min() == pytest.approx(EX1_DRILL_BOTTOM, abs=1e-9)
    assert drill.xyz[:, 2].min() + EX1_DRILL_POINT < -30.0 - 1.99       # the full diameter is through
    assert ream.xyz[:, 2].min() == pytest.approx(-30.0)                 # the reamer to the hole depth
    # DRILLING_TYPE_STRATEGY: half feed over the first 2 mm, 0.75 over the last 8 mm (of the drill's travel)
    down = drill.xyz[drill.kind == FEED]
    feeds = drill.feed[drill.kind == FEED]
    np.testing.assert_allclose(np.column_stack([down[:, 2], feeds]),
                               [(-2.0, 900.0), (EX1_DRILL_BOTTOM + 8.0, 1800.0), (EX1_DRILL_BOTTOM, 1350.0)])
    assert any("through hole" in note and "-38.009" in note for note in ex1_program.notes)
    # the reamer leaves the bore at feed, not rapid
    assert ream.kind[np.argmin(ream.xyz[:, 2]) + 1] == FEED


def test_regions_and_depths_agree_with_nist(ex1_program):
    segments = nist_segments()
    assert [name for name, _ in segments] == ["MILL 18MM", "SPIRAL_DRILL_20MM", "REAMER_22MM", "MILL 18MM"]
    face, drill, ream, rough, finish = ex1_program.operations
    assert sorted(nist_xy_levels(segments[0][1])) == xy_levels(face)
    nist_pocket = nist_xy_levels(segments[3][1])
    ours = our_xy_levels(rough, finish)
    assert sorted(nist_pocket) == pytest.approx(sorted(ours))
    for z in (-5.9, -2.0, -30.0):  # a roughing level, a finishing level, the floor
        assert ours[z] == pytest.approx(nist_pocket[z], abs=1e-4)
    assert ours[-5.9] == pytest.approx((55, 85, 40, 100))
    assert ours[-2.0] == pytest.approx((54, 86, 39, 101))
    for (_, calls), op in ((segments[1], drill), (segments[2], ream)):
        feeds = np.array([[float(v) for v in args[:3]] for name, args in calls if name == "STRAIGHT_FEED"])
        assert np.all(feeds[:, :2] == [20.0, 60.0]) and np.all(op.xyz[op.kind == FEED, :2] == [20.0, 60.0])
        if op is ream:
            assert feeds[:, 2].min() == op.xyz[:, 2].min() == -30.0
        else:
            # NIST drills to Z -37.1378 (7.1378 mm past the bottom); we go the point length + 2 mm,
            # to -38.0086: both put the full diameter (tip + 6.0086) below the Z -30 bottom.
            assert feeds[:, 2].min() == pytest.approx(-37.1378)
            assert op.xyz[:, 2].min() == pytest.approx(EX1_DRILL_BOTTOM)
            assert abs(op.xyz[:, 2].min() - feeds[:, 2].min()) < 1.0
            assert max(feeds[:, 2].min(), op.xyz[:, 2].min()) + EX1_DRILL_POINT < -30.0


# --------------------------------------------------------------------------- reordering


def operation_order(nc_text):
    return re.findall(r"^\(OPERATION \d+: (.*)\)$", nc_text, re.MULTILINE)


def test_swapping_workingsteps_swaps_operations_and_nc(ex1, ex1_program):
    order = [10, 13, 12, 11, 14]  # the drill and the roughing change places
    swapped = to_program(ex1, order=order)
    assert [op.name for op in swapped.operations] == [ex1.workingstep(i).its_id for i in order]
    linuxcnc = post.milling_post("linuxcnc")
    assert operation_order(linuxcnc.to_text(swapped)) == [ex1.workingstep(i).its_id.upper() for i in order]
    before = by_name(ex1_program)
    for op in swapped.operations:  # every operation is the same, only the order changed
        np.testing.assert_array_equal(op.xyz, before[op.name].xyz)
        np.testing.assert_array_equal(op.kind, before[op.name].kind)
        assert op.tool == before[op.name].tool
    assert not any("assumes" in note for note in swapped.notes)


def test_finishing_before_its_roughing_is_reported_not_replanned(ex1, ex1_program):
    swapped = to_program(ex1, order=[10, 11, 12, 14, 13])
    assert any("assumes roughing #13" in note for note in swapped.notes)
    # The cuts are the same; only where the pocket's middle is still uncut (the first floor layer
    # below the rough floor) the approach now stops above the material (test_stepnc_linking.py).
    early, planned = by_name(swapped)["WS FINISH POCKET1"], by_name(ex1_program)["WS FINISH POCKET1"]
    np.testing.assert_array_equal(early.kind, planned.kind)
    np.testing.assert_array_equal(early.xyz[:, :2], planned.xyz[:, :2])
    changed = np.flatnonzero(early.xyz[:, 2] != planned.xyz[:, 2])
    assert len(changed) == 1 and early.kind[changed[0]] == RAPID
    assert early.xyz[changed[0], 2] == pytest.approx(0.0 + 2.0)   # the pocket top (Z 0) + APPROACH_GAP
    assert early.xyz[changed[0], 2] > planned.xyz[changed[0], 2]
    disabled = to_program(ex1, enabled=[10, 11, 12, 14])
    assert [op.name for op in disabled.operations] == ["WS FINISH PLANAR FACE1", "WS DRILL HOLE1", "WS REAM HOLE1",
                                                        "WS FINISH POCKET1"]
    assert any("assumes roughing #13" in note for note in disabled.notes)


def test_finishing_region_is_what_roughing_leaves(ex1):
    rough = ex1.workingstep(13)
    leftover = finishing_leftover(rough.its_feature, [rough.its_operation])
    # the 1 mm allowance_side along the walls (the R9 tool leaves nothing more in the R10 corners)
    perimeter = 2 * (30 + 60) + 2 * math.pi * POCKET_RADIUS
    assert leftover.area() == pytest.approx(perimeter * 1.0 - math.pi * 1.0, rel=2e-3)
    assert finishing_leftover(rough.its_feature, []).area() == pytest.approx(pocket_region(rough.its_feature).area())


def test_bad_order_is_rejected(ex1):
    with pytest.raises(ValueError, match="missing \\[14\\]"):
        to_program(ex1, order=[10, 11, 12, 13])
    with pytest.raises(ValueError, match="unknown \\[99\\]"):
        to_program(ex1, order=[10, 11, 12, 13, 14, 99])


# --------------------------------------------------------------------------- variants of ex1


def test_both_spellings_give_the_same_program(ex1_program):
    text = ex1_text()
    text = text.replace("BIDIRECTIONAL_MILLING(", "BIDIRECTIONAL(")
    text = text.replace("MILLING_TOOL_DIMENSION(", "TOOL_DIMENSION(")
    text = text.replace("= PLANE(", "= ELEMENTARY_SURFACE(")
    program = to_program(load_workplan(text))
    for a, b in zip(program.operations, ex1_program.operations):
        np.testing.assert_array_equal(a.xyz, b.xyz)


def test_nested_workplans_are_flattened():
    text = replace_instance(ex1_text(), 2, "#2= WORKPLAN('MAIN WORKPLAN',(#10,#300,#14),$,#8,$);")
    text = add_instances(text, "#300= WORKPLAN('HOLE AND ROUGH',(#11,#12,#301),$,$,$);",
                         "#301= WORKPLAN('ROUGH',(#13),$,$,$);")
    loaded = load_workplan(text)
    assert [ws.id for ws in loaded.workingsteps] == [10, 11, 12, 13, 14]
    assert [op.name for op in to_program(loaded).operations][1:4] == ["WS DRILL HOLE1", "WS REAM HOLE1",
                                                                      "WS ROUGH POCKET1"]


def test_unsupported_feature_is_skipped_with_a_warning():
    text = replace_instance(ex1_text(), 2, "#2= WORKPLAN('MAIN WORKPLAN',(#10,#11,#200,#12,#203,#13,#14),$,#8,$);")
    text = add_instances(
        text,
        "#200= MACHINING_WORKINGSTEP('WS ROUGH STEP1',#62,#201,#22,$);",
        "#201= STEP('STEP1',#4,(#22),#84,#65,#24,#202,());",     # (SLOT is read since step19)
        "#202= VEE_PROFILE($,#58,90.,0.);",
        "#203= PROGRAM_STOP();")
    loaded = load_workplan(text)
    assert [ws.id for ws in loaded.workingsteps] == [10, 11, 12, 13, 14]
    assert any("#200" in w and "STEP #201 is not supported" in w for w in loaded.warnings)
    assert any("#203 PROGRAM_STOP" in w for w in loaded.warnings)
    program = to_program(loaded)
    assert len(program.operations) == 5
    assert any("STEP #201" in note for note in program.notes)


def test_unsupported_strategy_and_tilted_feature_are_skipped():
    text = replace_instance(ex1_text(), 51, "#51= CONTOUR_SPIRAL($,$,.CW.,.CONVENTIONAL.);")
    text = replace_instance(text, 81, "#81= AXIS2_PLACEMENT_3D('HOLE1',#110,#97,#111);")  # axis along X
    loaded = load_workplan(text)
    assert [ws.id for ws in loaded.workingsteps] == [10, 14]
    assert any("CONTOUR_SPIRAL #51 is not supported" in w and "#13" in w for w in loaded.warnings)
    assert sum("ROUND_HOLE #17 is not supported" in w for w in loaded.warnings) == 2


def test_zero_or_negative_spindle_speed_is_refused_naming_the_workingstep():
    text = replace_instance(ex1_text(), 45, "#45= MILLING_TECHNOLOGY(0.030,.TCP.,$,0.000,$,.F.,.F.,.F.,$);")
    with pytest.raises(StepNcError, match=r"workingstep #11 'WS DRILL HOLE1': #45 MILLING_TECHNOLOGY: "
                                          r"spindle speed 0 rpm \(spindle 0 rev/s\)"):
        to_program(load_workplan(text))
    # the spindle from a negative cutting speed: -1 m/s on the 22 mm reamer
    text = replace_instance(ex1_text(), 48, "#48= MILLING_TECHNOLOGY(0.030,.TCP.,-1.000,$,$,.F.,.F.,.F.,$);")
    with pytest.raises(StepNcError, match=r"workingstep #12 'WS REAM HOLE1': .*spindle speed -868\.\d+ rpm "
                                          r"\(cutspeed -1 m/s\)"):
        to_program(load_workplan(text))


def test_tools_are_named_as_what_they_are(ex1_program):
    ops = by_name(ex1_program)
    assert ops["WS REAM HOLE1"].tool.describe() == "T3 22 mm reamer (REAMER_22MM)"
    assert ops["WS DRILL HOLE1"].tool.describe() == "T2 20 mm twist drill (SPIRAL_DRILL_20MM)"
    assert ops["WS ROUGH POCKET1"].tool.describe() == "T1 18 mm flat end mill (MILL 18MM)"
    assert ops["WS REAM HOLE1"].tool.kind == "drill"        # the IR kind is unchanged
    text = post.milling_post("fanuc").to_text(ex1_program)
    tool_lines = [line for line in text.splitlines() if line.startswith("(TOOL:")]
    assert any("22 MM REAMER" in line for line in tool_lines), tool_lines
    assert not any("22 MM DRILL" in line for line in tool_lines)
    centre = replace_instance(ex1_text(), 31, "#31= CENTER_DRILL(#32,2,.RIGHT.,.F.,0.840);")
    program = to_program(load_workplan(centre))
    assert by_name(program)["WS DRILL HOLE1"].tool.describe() == "T2 20 mm centre drill (SPIRAL_DRILL_20MM)"
    # a centre drill is not a through-hole drill: no breakthrough below the hole's Z -30
    assert by_name(program)["WS DRILL HOLE1"].xyz[:, 2].min() == pytest.approx(-30.0)


POCKET1_AT = "#118= CARTESIAN_POINT('POCKET1: DEPTH ',(0.000,0.000,{z:.3f}));"
STOCK_BLOCK = ("#400= BLOCK('STOCK',#401,150.000,150.000,{h:.3f});",
               "#401= AXIS2_PLACEMENT_3D('STOCK',#402,#96,#97);",
               "#402= CARTESIAN_POINT('STOCK CORNER',(-10.000,-10.000,{z0:.3f}));")


def with_stock(text, bottom):
    """ex1 with a workpiece BLOCK from Z `bottom` up to Z 5 (the planar face's top)."""
    text = replace_instance(text, 4, "#4= WORKPIECE('SIMPLE WORKPIECE',#6,0.010,$,$,#400,(#66,#67,#68,#69));")
    return add_instances(text, *(line.format(h=5.0 - bottom, z0=bottom) for line in STOCK_BLOCK))


def test_feature_below_the_stock_bottom_is_refused():
    # ex1 has no workpiece BLOCK: its through hole's depth plane (Z -30) is the stock bottom.
    deep = replace_instance(ex1_text(), 118, POCKET1_AT.format(z=-35.0))
    with pytest.raises(StepNcError, match=r"workingstep #13 'WS ROUGH POCKET1': ClosedPocket #18 'POCKET1': its depth "
                                          r"reaches Z -35, 5 mm below the stock bottom \(Z -30, the depth of through "
                                          r"feature #17 'HOLE1 D=22MM'\)"):
        to_program(load_workplan(deep))
    # with a 45 mm stock (Z -40 .. 5) the same pocket fits; 1 mm below Z -40 does not
    finish = by_name(to_program(load_workplan(with_stock(deep, -40.0))))["WS FINISH POCKET1"]
    assert finish.xyz[:, 2].min() == pytest.approx(-35.0)
    deeper = with_stock(replace_instance(ex1_text(), 118, POCKET1_AT.format(z=-41.0)), -40.0)
    with pytest.raises(StepNcError, match=r"'WS ROUGH POCKET1'.*Z -41, 1 mm below the stock bottom \(Z -40, "
                                          r"the bottom of workpiece BLOCK #400\)"):
        to_program(load_workplan(deeper))
    # a blind hole (flat bottom) through a 25 mm stock: its Z -30 is 5 mm below the stock's Z -25
    blind = replace_instance(with_stock(ex1_text(), -25.0), 26, "#26= FLAT_HOLE_BOTTOM();")
    with pytest.raises(StepNcError, match=r"'WS DRILL HOLE1': RoundHole #17 'HOLE1 D=22MM': its depth reaches "
                                          r"Z -30, 5 mm below the stock bottom \(Z -25"):
        to_program(load_workplan(blind))
    # and a drill's cutting_depth past the bottom of a blind hole
    drilled = replace_instance(replace_instance(with_stock(ex1_text(), -40.0), 26, "#26= FLAT_HOLE_BOTTOM();"),
                               20, "#20= DRILLING($,$,'DRILL HOLE1',10.000,$,#44,#45,#41,$,42.000,$,$,$,#46);")
    with pytest.raises(StepNcError, match=r"'WS DRILL HOLE1': .*its cutting_depth 42 reaches Z -42, 2 mm below"):
        to_program(load_workplan(drilled))


def test_through_hole_breakthrough_from_the_file():
    # overcut_length (attribute 8 of DRILLING) says how far past the bottom the drill goes: 3.5 mm
    text = replace_instance(ex1_text(), 20, "#20= DRILLING($,$,'DRILL HOLE1',10.000,$,#44,#45,#41,3.500,$,$,$,$,#46);")
    drill = by_name(to_program(load_workplan(text)))["WS DRILL HOLE1"]
    assert drill.xyz[:, 2].min() == pytest.approx(-33.5)
    # an explicit cutting_depth on a through hole is the file's own breakthrough: not refused
    text = replace_instance(ex1_text(), 20, "#20= DRILLING($,$,'DRILL HOLE1',10.000,$,#44,#45,#41,$,36.000,$,$,$,#46);")
    drill = by_name(to_program(load_workplan(text)))["WS DRILL HOLE1"]
    assert drill.xyz[:, 2].min() == pytest.approx(-36.0)


def test_unknown_stock_bottom_is_reported():
    text = replace_instance(ex1_text(), 26, "#26= FLAT_HOLE_BOTTOM();")    # no through feature, no BLOCK
    program = to_program(load_workplan(text))
    assert any("stock bottom is unknown" in note for note in program.notes)
    assert not any("stock bottom is unknown" in note for note in to_program(load_workplan(ex1_text())).notes)


def test_dangling_reference_names_the_instance():
    text = ex1_text().replace("(#22,#23),#84,#65", "(#22,#23),#999,#65")  # #18's feature_placement
    with pytest.raises(Part21Error, match=r"#999") as error:
        load_workplan(text)
    assert error.value.instance_id == 18


def test_wrong_entity_for_a_placement_names_instance_and_attribute():
    text = ex1_text().replace("(#22,#23),#84,#65", "(#22,#23),#115,#65")  # a CARTESIAN_POINT
    with pytest.raises(StepNcError, match=r"#18 CLOSED_POCKET: attribute feature_placement must refer to "
                                          r"AXIS2_PLACEMENT_3D, found #115 CARTESIAN_POINT"):
        load_workplan(text)


def test_missing_and_unset_attributes_name_instance_and_attribute():
    text = replace_instance(ex1_text(), 40, "#40= MILLING_TECHNOLOGY(0.040,.TCP.,$);")
    with pytest.raises(StepNcError, match=r"#40 MILLING_TECHNOLOGY: attribute spindle \(number 4\) is missing"):
        load_workplan(text)
    text = replace_instance(ex1_text(), 73, "#73= AXIS2_PLACEMENT_3D('PLANE1',$,#99,#100);")
    with pytest.raises(StepNcError, match=r"#73 AXIS2_PLACEMENT_3D: attribute location is unset"):
        load_workplan(text)
    with pytest.raises(StepNcError, match="exactly one PROJECT"):
        load_workplan(replace_instance(ex1_text(), 1, "#1= DESCRIPTIVE_PARAMETER('NO PROJECT','');"))


def test_helix_and_ramp_approaches(ex1):
    text = replace_instance(ex1_text(), 22, "#22= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET1',15.000,$,#39,#50,"
                                            "#41,$,#200,#201,#51,6.500,5.000,1.000,0.500);")
    text = replace_instance(text, 23, "#23= BOTTOM_AND_SIDE_FINISH_MILLING($,$,'FINISH POCKET1',15.000,$,#39,#52,"
                                      "#41,$,#201,$,#53,2.000,10.000,$,$);")
    text = add_instances(text, "#200= PLUNGE_HELIX($,4.0,10.0);", "#201= PLUNGE_RAMP($,20.0);")
    program = to_program(load_workplan(text))
    rough, finish = by_name(program)["WS ROUGH POCKET1"], by_name(program)["WS FINISH POCKET1"]
    arcs = rough.kind == ARC_CCW
    assert arcs.sum() >= 5   # at least one helical turn per layer
    centres = rough.center[arcs]
    assert rounded_rect_wall_distance(centres).min() >= MILL_RADIUS + 1.0 + 4.0 - 1e-6  # the helix fits the region
    climb = np.diff(np.concatenate([[rough.start[2]], rough.xyz[:, 2]]))[arcs]
    assert np.all(climb <= 0) and (climb < 0).sum() >= 5
    # down at exactly the file's 10 degrees (pitch = pi D tan 10), then round at the layer to the start
    a, b, c = rough.start_points()[arcs], rough.xyz[arcs], rough.center[arcs]
    sweep = (np.arctan2(b[:, 1] - c[:, 1], b[:, 0] - c[:, 0]) - np.arctan2(a[:, 1] - c[:, 1], a[:, 0] - c[:, 0])) \
        % (2 * math.pi)
    sweep[sweep < 1e-9] = 2 * math.pi
    slope = np.degrees(np.arctan2(-climb, 4.0 * sweep))
    assert np.allclose(slope[climb < 0], 10.0, atol=1e-6)
    # retract along the ramp: the same strategy backwards, ending where the approach started
    a, b = finish.start_points(), finish.xyz
    run, drop = np.linalg.norm(b[:, :2] - a[:, :2], axis=1), np.abs(b[:, 2] - a[:, 2])
    ramping = (finish.kind == FEED) & (drop > 1e-9) & (run > 1e-9)
    slope = np.degrees(np.arctan2(drop[ramping], run[ramping]))
    assert ramping.sum() > 0 and slope.max() <= 20.0 + 1e-6
    assert rounded_rect_wall_distance(b[ramping]).min() >= MILL_RADIUS - 0.01  # ramps stay on the path
    assert xy_levels(finish) == xy_levels(by_name(to_program(ex1))["WS FINISH POCKET1"])


def obround_text() -> str:
    """ex1 with an obround pocket: a COMPOSITE_CURVE of TRIMMED_CURVE lines (by parameter), a
    TRIMMED_CURVE circle (by points), a POLYLINE and a reversed semicircle."""
    text = replace_instance(ex1_text(), 28, "#28= GENERAL_CLOSED_PROFILE($,#400);")
    return add_instances(
        text,
        "#400= COMPOSITE_CURVE('OBROUND',(#401,#402,#403,#404),.F.);",
        "#401= COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#410);",
        "#402= COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#420);",
        "#403= COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#430);",
        "#404= COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.F.,#440);",
        "#410= TRIMMED_CURVE('',#411,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(60.)),.T.,.PARAMETER.);",
        "#411= LINE('',#412,#413);", "#412= CARTESIAN_POINT('',(-30.,-20.,0.));",
        "#413= VECTOR('',#414,1.);", "#414= DIRECTION('',(1.,0.,0.));",
        "#420= TRIMMED_CURVE('',#421,(#424),(#425),.T.,.CARTESIAN.);",
        "#421= CIRCLE('',#422,20.);", "#422= AXIS2_PLACEMENT_3D('',#423,$,$);",
        "#423= CARTESIAN_POINT('',(30.,0.,0.));",
        "#424= CARTESIAN_POINT('',(30.,-20.,0.));", "#425= CARTESIAN_POINT('',(30.,20.,0.));",
        "#430= POLYLINE('',(#425,#431));", "#431= CARTESIAN_POINT('',(-30.,20.,0.));",
        "#440= TRIMMED_CURVE('',#441,(PARAMETER_VALUE(270.)),(PARAMETER_VALUE(90.)),.F.,.PARAMETER.);",
        "#441= CIRCLE('',#442,20.);", "#442= AXIS2_PLACEMENT_3D('',#443,$,$);",
        "#443= CARTESIAN_POINT('',(-30.,0.,0.));")


def unidirectional_text() -> str:
    """ex1 with the pocket roughed by one-way strokes along the pocket's length (world +Y)."""
    text = replace_instance(ex1_text(), 51, "#51= UNIDIRECTIONAL_MILLING($,.T.,#500,.CLIMB.);")
    return add_instances(text, "#500= DIRECTION('ALONG THE POCKET',(1.,0.,0.));")


def test_unidirectional_strokes_all_run_one_way():
    rough = by_name(to_program(load_workplan(unidirectional_text())))["WS ROUGH POCKET1"]
    a, b = rough.start_points(), rough.xyz
    level = (rough.kind == FEED) & (np.abs(a[:, 2] - b[:, 2]) < 1e-9)
    inner = level & (np.abs(a[:, 0] - b[:, 0]) < 1e-9) & (a[:, 0] > 55 + 1e-6) & (a[:, 0] < 85 - 1e-6)
    assert inner.sum() >= 5 * 5                 # several strokes per layer, away from the outline ring
    assert np.all(b[inner, 1] > a[inner, 1])    # all along +Y, none back
    assert rounded_rect_wall_distance(cut_points(rough)).min() >= MILL_RADIUS + 1.0 - 1e-6


def test_general_profile_of_lines_and_arcs():
    loaded = load_workplan(obround_text())
    pocket = loaded.workingstep(13).its_feature
    assert isinstance(pocket.feature_boundary, GeneralClosedProfile)
    # the profile's x axis is the pocket's ref_direction, world +Y: 100 long in Y, 40 wide in X
    outline = pocket.outline()
    assert outline.min(axis=0) == pytest.approx([50, 20], abs=1e-6)
    assert outline.max(axis=0) == pytest.approx([90, 120], abs=1e-6)
    assert rg.area(rg.from_loops([outline])) == pytest.approx(60 * 40 + math.pi * 400, abs=0.1)
    program = to_program(loaded)
    finish = by_name(program)["WS FINISH POCKET1"]
    walls = cut_points(finish)
    walls = walls[walls[:, 2] > -29.5]
    # obround: distance to the wall = 20 - distance to the middle segment X 70, Y 40..100
    to_spine = np.hypot(walls[:, 0] - 70, walls[:, 1] - np.clip(walls[:, 1], 40, 100))
    assert np.abs((20 - to_spine) - MILL_RADIUS).max() <= 0.01


# --------------------------------------------------------------------------- pockets -> Part 21 -> workplan


def test_two_pockets_round_trip(two_pockets):
    text, loaded = two_pockets
    assert loaded.warnings == ()
    assert [ws.its_id for ws in loaded.workingsteps] == [
        "WS ROUGH POCKET 1", "WS FINISH POCKET 1", "WS ROUGH POCKET 2", "WS FINISH POCKET 2"]
    assert loaded.project.its_workpieces[0].its_bounding_geometry.box() == STOCK
    for spec, index in zip(TWO_POCKETS, (0, 2)):
        rough, finish = loaded.workingsteps[index], loaded.workingsteps[index + 1]
        pocket = rough.its_feature
        assert finish.its_feature is pocket and pocket.its_id == spec.name
        assert pocket.top_z == 0.0 and pocket.bottom_z == -spec.depth
        assert (pocket.orthogonal_radius or 0.0) == spec.corner_radius
        written = rg.from_loops([spec.outline])
        assert rg.area(rg.from_loops([pocket.outline()]) ^ written) == pytest.approx(written.area(), abs=1e-9)
        assert rg.area(rg.from_loops([pocket.outline()]) - written) < 1e-9
        op = rough.its_operation
        assert (op.axial_cutting_depth, op.allowance_side, op.allowance_bottom) == (2.0, 0.5, 0.2)
        assert isinstance(op.its_machining_strategy, Bidirectional) and op.its_machining_strategy.overlap == 0.5
        assert isinstance(finish.its_operation.its_machining_strategy, ContourParallel)
        assert op.its_tool.its_id == "T1 FLAT 4MM" and op.its_tool.its_tool_body.dimension.diameter == 4.0  # T number first
        assert op.its_technology.feed_mm_min == pytest.approx(600.0)
        assert op.its_technology.spindle_rpm == pytest.approx(12000.0)
    assert isinstance(loaded.workingsteps[0].its_feature.feature_boundary, RectangularClosedProfile)
    assert isinstance(loaded.workingsteps[2].its_feature.feature_boundary, GeneralClosedProfile)
    # written again from what was read, the same file
    again = [PocketSpec(ws.its_feature.its_id, tuple(map(tuple, ws.its_feature.outline())), -ws.its_feature.bottom_z,
                        ws.its_feature.orthogonal_radius or 0.0) for ws in loaded.workingsteps[::2]]
    rewritten = pockets_to_part21(STOCK, again, FLAT_4, feed=600.0, spindle_rpm=12000.0, axial_depth=2.0,
                                  allowance_side=0.5, allowance_bottom=0.2)
    assert load_workplan(rewritten).workingsteps == loaded.workingsteps


def test_paper_reordering_of_two_pockets(two_pockets):
    """The paper swaps #9 (pocket 1 finishing) with #10 (pocket 2 roughing)."""
    _, loaded = two_pockets
    r1, f1, r2, f2 = (ws.id for ws in loaded.workingsteps)
    original, swapped = to_program(loaded), to_program(loaded, order=[r1, r2, f1, f2])
    assert [op.name for op in swapped.operations] == ["WS ROUGH POCKET 1", "WS ROUGH POCKET 2",
                                                      "WS FINISH POCKET 1", "WS FINISH POCKET 2"]
    text = post.milling_post("fanuc").to_text(swapped)
    assert operation_order(text) == ["WS ROUGH POCKET 1", "WS ROUGH POCKET 2", "WS FINISH POCKET 1",
                                     "WS FINISH POCKET 2"]
    before = by_name(original)
    for op in swapped.operations:
        np.testing.assert_array_equal(op.xyz, before[op.name].xyz)
    assert swapped.notes == []  # pocket 1 is still roughed before it is finished


def test_two_pockets_rough_inside_allowance_and_finish_on_the_walls(two_pockets):
    _, loaded = two_pockets
    ops = by_name(to_program(loaded))
    r = FLAT_4.radius
    rect_centre, rect_half = np.array([25.0, 20.0]), np.array([15.0, 10.0])
    l_shape = np.array(TWO_POCKETS[1].outline)
    for name, wall in (("POCKET 1", lambda p: rounded_rect_wall_distance(p, rect_centre, rect_half, 3.0)),
                       ("POCKET 2", lambda p: polygon_wall_distance(p, l_shape))):
        depth = next(spec.depth for spec in TWO_POCKETS if spec.name == name)
        rough, finish = ops[f"WS ROUGH {name}"], ops[f"WS FINISH {name}"]
        assert wall(cut_points(rough)).min() >= r + 0.5 - 0.01   # links at depth may stray LINK_TOLERANCE
        assert rough.xyz[:, 2].min() == pytest.approx(-depth + 0.2)
        assert finish.xyz[:, 2].min() == pytest.approx(-depth)
        points = cut_points(finish)
        assert wall(points).min() >= r - 0.01                       # never into the wall
        walls = points[points[:, 2] > -depth + 0.2 + 1e-9]
        assert np.abs(wall(walls) - r).max() <= 0.01                # only the allowance, edge on the wall
        # ramps (5 degrees) stay on the paths, inside the region
        assert wall(rough.xyz[rough.kind == FEED]).min() >= r + 0.5 - 0.01


def test_pockets_to_part21_rejects_bad_input():
    with pytest.raises(ValueError, match="no volume"):
        pockets_to_part21(((0, 0, 0), (10, 10, 0)), TWO_POCKETS, FLAT_4)
    with pytest.raises(ValueError, match="depth"):
        pockets_to_part21(STOCK, [PocketSpec("DEEP", TWO_POCKETS[0].outline, 25.0)], FLAT_4)
    with pytest.raises(ValueError, match="end mill"):
        pockets_to_part21(STOCK, TWO_POCKETS, Tool(2, "drill", 4.0))
    with pytest.raises(rg.RegionError, match="BAD"):
        pockets_to_part21(STOCK, [PocketSpec("BAD", ((0, 0), (1, 1)), 1.0)], FLAT_4)


# --------------------------------------------------------------------------- every program through rs274


@functools.lru_cache(maxsize=1)
def program_variants():
    ex1 = load_workplan(EX1)
    two = load_workplan(pockets_to_part21(STOCK, TWO_POCKETS, FLAT_4, feed=600.0, spindle_rpm=12000.0,
                                          axial_depth=2.0))
    ids = [ws.id for ws in two.workingsteps]
    helix = replace_instance(ex1_text(), 22, "#22= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET1',15.000,$,#39,"
                                             "#50,#41,$,#200,#200,#51,6.500,5.000,1.000,0.500);")
    helix = add_instances(helix, "#200= PLUNGE_HELIX($,4.0,10.0);")
    return {
        "ex1": to_program(ex1),
        "ex1 reordered": to_program(ex1, order=[10, 13, 14, 11, 12]),
        "two pockets": to_program(two),
        "two pockets, paper order": to_program(two, order=[ids[0], ids[2], ids[1], ids[3]]),
        "ex1 helix": to_program(load_workplan(helix)),
        "obround": to_program(load_workplan(obround_text())),
        "ex1 unidirectional": to_program(load_workplan(unidirectional_text())),
    }


@needs_rs274
@pytest.mark.parametrize("name", ["ex1", "ex1 reordered", "two pockets", "two pockets, paper order", "ex1 helix",
                                  "obround", "ex1 unidirectional"])
def test_linuxcnc_program_passes_rs274_and_matches_the_ir(name):
    writer = post.milling_post("linuxcnc")
    program = program_variants()[name]
    kinds, points, _ = rs274.motion_endpoints(rs274.run(writer.to_text(program)))
    cutting = [i for i, kind in enumerate(kinds) if kind != "rapid"]
    # the program as the post writes it: the pockets' rounded corners as arcs (test_arcs_out.py
    # checks those against the polylines), every other move as planned
    want_kinds, want_points = expected_cutting_endpoints(writer.arcs_out(program))
    assert [kinds[i] for i in cutting] == want_kinds
    assert np.max(np.abs(points[cutting] - want_points)) < 1e-3
