"""toolpath/ir/kinematics.py: machine <-> part for the C-X-Z table and the X-Z-C turn-mill, and the
length convention of a move that turns C."""
import math

import numpy as np
import pytest

from kezuri.post.rotary_cxz import RotaryCXZPost
from kezuri.post.turnmill_xzc import TurnMillXZCPost
from kezuri.toolpath.ir import kinematics as kin
from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Program, Tool
from kezuri.toolpath.ir.program import TurnMillOperation

RNG = np.random.default_rng(20261125)


def angle_difference(a, b):
    """a - b in degrees, folded into [-180, 180)."""
    return (np.asarray(a) - np.asarray(b) + 180.0) % 360.0 - 180.0


# ----- round trips ----------------------------------------------------------------------------
def test_cxz_machine_to_part_to_machine_round_trip():
    x = -RNG.uniform(0.01, 80.0, 500)                     # X = -R: the tool stays on the negative side
    c = RNG.uniform(-720.0, 720.0, 500)                   # unwrapped C, several turns
    z = RNG.uniform(-30.0, 5.0, 500)
    part = kin.machine_to_part(np.column_stack([x, np.zeros(500), z]), c)
    x_back, c_back = kin.to_cylindrical(part[:, :2])
    assert np.allclose(x_back, x, atol=1e-9)
    assert np.allclose(angle_difference(c_back, c), 0.0, atol=1e-7)
    assert np.all((c_back > -180.0) & (c_back <= 180.0))
    # along a path (neighbours within half a turn) unwrapping gives the C words back as they were
    steady = np.cumsum(RNG.uniform(-170.0, 170.0, 500))   # a path: neighbours within half a turn
    part = kin.machine_to_part(np.column_stack([x, np.zeros(500), z]), steady)
    x_back, c_back = kin.to_cylindrical(part[:, :2])
    assert np.allclose(kin.unwrap_c(c_back, -x_back, start_c=steady[0]), steady, atol=1e-7)


def test_cxz_part_to_machine_to_part_round_trip():
    xy = RNG.uniform(-60.0, 60.0, (500, 2))
    x, c = kin.to_cylindrical(xy)
    assert np.all(x <= 0)
    assert np.allclose(kin.from_cylindrical(x, c), xy, atol=1e-9)
    assert np.allclose(kin.from_cylindrical(x, c + 360.0), xy, atol=1e-9)


def test_xzc_machine_to_part_to_machine_round_trip():
    r = RNG.uniform(0.01, 40.0, 500)                      # X = +R on a turn-mill
    c = RNG.uniform(-720.0, 720.0, 500)
    z = RNG.uniform(-60.0, 2.0, 500)
    part = kin.machine_to_part(np.column_stack([r, np.zeros(500), z]), c)
    rho, angle = kin.polar(part)
    assert np.allclose(rho, r, atol=1e-9)
    assert np.allclose(angle_difference(np.degrees(angle), c), 0.0, atol=1e-7)
    assert np.allclose(part[:, 2], z)
    back = kin.machine_to_part(np.column_stack([rho, np.zeros(500), part[:, 2]]), np.degrees(angle))
    assert np.allclose(back, part, atol=1e-9)


def test_xzc_part_to_machine_to_part_round_trip_and_the_axis():
    points = RNG.uniform(-40.0, 40.0, (500, 3))
    points[[10, 11, 300]] = [[0.0, 0.0, 1.0], [0.0, 0.0, -2.0], [0.0, 0.0, 3.0]]   # on the axis
    rho, angle = kin.polar(points)
    back = kin.machine_to_part(np.column_stack([rho, np.zeros(500), points[:, 2]]), np.degrees(angle))
    assert np.allclose(back, points, atol=1e-9)
    assert angle[10] == angle[11] == angle[9] and angle[300] == angle[299]   # on the axis: the angle before


# ----- sign conventions, as the posts' headers state them --------------------------------------
def test_cxz_signs_match_the_post_header():
    header = " ".join(RotaryCXZPost.conventions)
    assert "X = -R FROM THE AXIS" in header and "+C TURNS THE TABLE CLOCKWISE SEEN FROM THE TOOL" in header
    r = 25.0
    # X = -R: the part point on the part's -X axis is under the tool at C = 0.
    x, c = kin.to_cylindrical([[-r, 0.0]])
    assert x[0] == pytest.approx(-r) and c[0] == pytest.approx(0.0)
    # C is measured counter-clockwise (seen from +Z, the tool side) from the part's -X axis.
    x, c = kin.to_cylindrical([[0.0, -r], [r, 0.0], [0.0, r]])
    assert np.allclose(c, [90.0, 180.0, -90.0])
    # +C turns the table clockwise seen from the tool: a fixed part point's machine position
    # R(-C) p turns clockwise (negative angle about +Z) as C grows ...
    p = kin.machine_to_part([[-r, 0.0, 0.0]], [0.0])[0]          # the part point under the tool at C = 0

    def machine_angle(c_deg):                                    # where p is on the machine at C
        m = kin.machine_to_part([p], [-c_deg])[0]                # R(-C) p (machine_to_part turns by its C)
        return math.degrees(math.atan2(m[1], m[0]))
    assert angle_difference(machine_angle(10.0), machine_angle(0.0)) == pytest.approx(-10.0)
    # ... so the tool, fixed on the machine, moves counter-clockwise over the part.
    tip = kin.machine_to_part([[-r, 0.0, 0.0], [-r, 0.0, 0.0]], [0.0, 10.0])
    assert np.cross(tip[0, :2], tip[1, :2]) > 0


def test_xzc_signs_match_the_post_header_and_the_plan_notes():
    program = Program("p", [TurnMillOperation("o", Tool(1, "ball", 6.0), 1000, [FEED], [[20.0, 0.0, -5.0]], [100.0],
                                               rotary={"c": [90.0]}, start=[30.0, 0.0, 2.0])])
    header = "\n".join(TurnMillXZCPost().header(program))
    assert "C: PART ANGLE AT THE TOOL IN DEGREES" in header and "X: TOOL TIP DIAMETER" in header
    # C is the part angle atan2(y, x), brought to the tool on the machine's +X side; X the radius.
    assert np.allclose(kin.machine_to_part([[20.0, 0.0, -5.0]], [90.0]), [[0.0, 20.0, -5.0]], atol=1e-12)
    rho, angle = kin.polar(np.array([[0.0, 20.0, -5.0]]))
    assert rho[0] == pytest.approx(20.0) and math.degrees(angle[0]) == pytest.approx(90.0)
    # the radial tool points along machine +X (tip towards holder), i.e. outward at the part angle
    assert np.allclose(kin.radial_axes([90.0]), [[0.0, 1.0, 0.0]], atol=1e-12)


# ----- the length convention ---------------------------------------------------------------------
@pytest.mark.parametrize("x", [-25.0, 25.0, -3.5])
def test_a_full_c_turn_at_radius_r_is_two_pi_r(x):
    a = np.array([[x, 0.0, -1.0]])
    length = kin.traced_lengths(a, a, np.array([30.0]), np.array([390.0]))
    assert length[0] == pytest.approx(2 * math.pi * abs(x), rel=1e-12)
    # a helix: the turn and a Z feed together
    helix = kin.traced_lengths(a, a + [0.0, 0.0, -4.0], np.array([0.0]), np.array([-360.0]))
    assert helix[0] == pytest.approx(math.hypot(2 * math.pi * abs(x), 4.0), rel=1e-12)


def test_an_arc_of_c_is_its_arc_length_and_no_c_is_the_straight_length():
    a = np.array([[-10.0, 0.0, 0.0], [-3.0, 0.0, 1.0]])
    b = np.array([[-10.0, 0.0, 0.0], [-7.0, 0.0, -2.0]])
    lengths = kin.traced_lengths(a, b, np.array([0.0, 15.0]), np.array([45.0, 15.0]))
    assert lengths[0] == pytest.approx(10.0 * math.pi / 4, rel=1e-12)
    assert lengths[1] == pytest.approx(5.0, rel=1e-12)


def test_the_traced_length_is_the_length_of_the_interpolated_curve():
    """Against a fine polyline of the linear X/C/Z motion (radius changing while C turns)."""
    x0, c0, z0, x1, c1, z1 = -5.0, 10.0, 0.0, -30.0, 130.0, -3.0
    t = np.linspace(0.0, 1.0, 200001)
    n = len(t)
    curve = kin.interpolate(np.full(n, x0), np.full(n, c0), np.full(n, z0), np.full(n, x1), np.full(n, c1),
                            np.full(n, z1), t)
    polyline = np.linalg.norm(np.diff(curve, axis=0), axis=1).sum()
    traced = kin.traced_lengths(np.array([[x0, 0, z0]]), np.array([[x1, 0, z1]]), np.array([c0]), np.array([c1]))[0]
    assert traced == pytest.approx(polyline, rel=1e-6)
    chord = kin.chord_lengths(np.array([[x0, 0, z0]]), np.array([[x1, 0, z1]]), np.array([c0]), np.array([c1]))[0]
    assert chord < traced


def test_operations_measure_moves_as_documented():
    """Every C operation, the turn-mill's included, measures along the traced curve: a quarter turn
    at radius 20 is 10 pi long (the chord would be 20 sqrt 2)."""
    kind, xyz, c = [FEED, FEED], [[-20.0, 0.0, 0.0], [-20.0, 0.0, 0.0]], [0.0, 360.0]
    op = Operation("o", Tool(1, "ball", 6.0), 1000, kind, xyz, [100.0, 100.0], rotary={"c": c}, start=[-20, 0, 0])
    assert np.allclose(op.move_lengths(), [0.0, 2 * math.pi * 20.0])
    turn = TurnMillOperation("t", Tool(1, "ball", 6.0), 1000, kind, np.abs(xyz), [100.0, 100.0],
                             rotary={"c": [0.0, 90.0]}, start=[20, 0, 0])
    assert np.allclose(turn.move_lengths(), [0.0, 10.0 * math.pi])


def test_table_timing_uses_the_traced_length_and_the_table_speed():
    x = -10.0
    op = Operation("o", Tool(1, "ball", 6.0), 1000, [RAPID, FEED], [[x, 0, 0], [x, 0, 0]], [np.nan, 600.0],
                   rotary={"c": [0.0, 360.0]}, start=[x, 0, 5])
    seconds = kin.move_times(op, rapid_rate=5000.0, max_table_rpm=60.0)
    assert seconds[0] == pytest.approx(5.0 / 5000.0 * 60.0)
    assert seconds[1] == pytest.approx(2 * math.pi * 10.0 / 600.0 * 60.0)       # the feed is slower than 1 turn/s
    fast = kin.move_times(op, rapid_rate=5000.0, max_table_rpm=0.5)
    assert fast[1] == pytest.approx(120.0)                                      # limited by the table: 2 min a turn
    f = kin.inverse_time_feed(op, max_table_rpm=60.0)
    assert np.isnan(f[0]) and f[1] == pytest.approx(600.0 / (2 * math.pi * 10.0))
    assert kin.cycle_time(op, 5000.0, 60.0) == pytest.approx(seconds.sum())


def test_traced_lengths_are_kept_only_while_the_moves_match():
    """A full C turn at machine X = 20 is 2 pi 20 on the part; moving the tool to X = 10 in place
    (the arrays edited, not replaced) gives 2 pi 10, and the returned array is the caller's own."""
    op = Operation("o", Tool(1, "ball", 6.0), 1000, np.array([FEED, FEED], np.int8),
                   np.array([[20.0, 0.0, -5.0], [20.0, 0.0, -5.0]]), np.array([100.0, 100.0]),
                   rotary={"c": np.array([0.0, 360.0])}, start=np.array([20.0, 0.0, -5.0]))
    first = op.move_lengths()
    assert first == pytest.approx([0.0, 2 * math.pi * 20.0], rel=1e-9)
    first[:] = -1.0
    assert op.move_lengths() == pytest.approx([0.0, 2 * math.pi * 20.0], rel=1e-9)
    op.xyz[:, 0] = 10.0
    op.start[0] = 10.0
    assert op.move_lengths() == pytest.approx([0.0, 2 * math.pi * 10.0], rel=1e-9)
    op.rotary["c"][1] = 180.0
    assert op.move_lengths() == pytest.approx([0.0, math.pi * 10.0], rel=1e-9)
