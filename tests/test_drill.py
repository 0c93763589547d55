"""Drilling: holes found in curves and meshes, canned cycles (G81/G82/G83) read back by LinuxCNC's
rs274 and the rules checker, helix-milled holes and drilled holes cut in the simulation and
measured against closed forms, the visiting order."""
import math

import numpy as np
import pytest

import controller_rules
import rs274
from kezuri.post.fanuc import FanucPost
from kezuri.post.grbl import GrblPost
from kezuri.post.linuxcnc import LinuxCNCPost
from kezuri.toolpath import job as jobs
from kezuri.toolpath.ir.cycles import CycleError, DrillCycle
from kezuri.toolpath.ir.program import FEED, Program, ProgramError, Tool
from kezuri.toolpath.operations.drill import drill, holes
from kezuri.toolpath.operations.drill.helix import plan_helix
from kezuri.toolpath.operations.drill.kind import DrillGeometry
from kezuri.toolpath.operations.drill.order import short_order, tour_length
from kezuri.toolpath.simulate import BoxStock, simulate

HOLES = [(10.0, 10.0), (30.0, 10.0), (30.0, 25.0), (12.0, 28.0)]


# ----- holes found in curves and meshes ---------------------------------------------------------

@pytest.mark.parametrize("count", [32, 48, 64, 100, 128])
def test_circles_found_in_closed_curves(count):
    rng = np.random.default_rng(count)
    cx, cy, d = rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(2, 30)
    t = np.linspace(0, 2 * np.pi, count, endpoint=False) + rng.uniform(0, 1)
    loop = np.column_stack([cx + d / 2 * np.cos(t), cy + d / 2 * np.sin(t)])
    loop += rng.normal(0, 0.001, loop.shape)                       # within the 0.01 mm tolerance
    square = np.concatenate([np.column_stack([np.linspace(0, 10, 10, endpoint=False), np.zeros(10)]),
                             np.column_stack([np.full(10, 10.0), np.linspace(0, 10, 10, endpoint=False)]),
                             np.column_stack([np.linspace(10, 0, 10, endpoint=False), np.full(10, 10.0)]),
                             np.column_stack([np.zeros(10), np.linspace(10, 0, 10, endpoint=False)])])
    ellipse = np.column_stack([5 * np.cos(t), 5.2 * np.sin(t)])
    half = np.column_stack([5 * np.cos(t / 2), 5 * np.sin(t / 2)])  # a half circle closed by its chord
    found = holes.circles_in_curves([square, loop, ellipse, half])
    assert len(found) == 1
    assert found[0].x == pytest.approx(cx, abs=0.002) and found[0].y == pytest.approx(cy, abs=0.002)
    assert found[0].diameter == pytest.approx(d, abs=0.003)


def plate_with_holes():
    """A 60 x 40 x 10 plate (top Z 0) with a 64-segment 8 mm through hole at (15, 20) and a 64-segment
    12 mm hole 6 mm deep at (42, 20) (manifold3d's cylinders: vertices on the circle)."""
    import manifold3d as m3d
    plate = m3d.Manifold.cube((60, 40, 10)).translate((0, 0, -10))
    through = m3d.Manifold.cylinder(14, 4.0, 4.0, 64).translate((15, 20, -12))
    blind = m3d.Manifold.cylinder(10, 6.0, 6.0, 64).translate((42, 20, -6))
    mesh = (plate - through - blind).to_mesh()
    return np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts)


def test_cylindrical_holes_found_in_a_mesh():
    vertices, faces = plate_with_holes()
    found = holes.cylinder_holes(vertices, faces)
    assert len(found) == 2                       # the plate's four side walls are not circles
    a, b = found
    assert (a.x, a.y, a.diameter) == pytest.approx((15, 20, 8), abs=1e-6)
    assert (a.top, a.bottom, a.through) == (pytest.approx(0), pytest.approx(-10), True)
    assert (b.x, b.y, b.diameter) == pytest.approx((42, 20, 12), abs=1e-6)
    assert (b.top, b.bottom, b.through) == (pytest.approx(0), pytest.approx(-6), False)


def test_a_boss_is_not_a_hole():
    import manifold3d as m3d
    mesh = m3d.Manifold.cylinder(10, 5.0, 5.0, 64).to_mesh()
    assert holes.cylinder_holes(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts)) == []


# ----- canned cycles: the IR, the posts, rs274 and the rules -----------------------------------

def posted(op, post):
    return post.to_text(Program("holes", [op]))


def feed_ends(calls):
    kinds, points, _ = rs274.motion_endpoints(calls)
    return points[[k == "feed" for k in kinds]]


@pytest.mark.parametrize("peck, dwell, code", [(0.0, 0.0, "G81"), (0.0, 0.5, "G82"), (2.5, 0.0, "G83")])
@pytest.mark.parametrize("retract, level", [("initial", "G98"), ("r", "G99")])
def test_rs274_runs_the_cycles_to_the_expanded_moves_bottoms(peck, dwell, code, retract, level):
    settings = drill.DrillSettings(peck=peck, dwell=dwell, retract=retract, depth=8.0)
    op = drill.plan(HOLES, settings, top=0.0)
    assert op.cycle.kind == {"G81": "drill", "G82": "dwell", "G83": "peck"}[code]
    text = posted(op, LinuxCNCPost())
    assert f"{level} {code} X10. Y10. Z-8. R2." in text and "\nG80\n" in text
    assert text.count("\nX") == 3                               # the next three holes: X Y blocks
    calls = rs274.run(text, tools=[4])
    # every feed rs274's cycle makes ends where the expanded moves' feed moves end: the pecks'
    # depths (2 mm above the top less 2.5 mm a peck) and each hole's bottom at Z-8
    expected = op.xyz[op.kind == FEED]
    assert np.allclose(feed_ends(calls), expected, atol=1e-4)
    bottoms = {(x, y) for x, y, z in feed_ends(calls) if abs(z + 8.0) < 1e-6}
    assert bottoms == set(HOLES)
    if dwell:
        assert [args for name, args in calls if name == "DWELL"] == [["0.5000"]] * 4
    kinds, points, _ = rs274.motion_endpoints(calls)
    # between holes the tool travels at the initial level (G98: Z20) or the R plane (G99: Z2)
    travel = [p for k, p, q in zip(kinds, points[1:], points[:-1]) if k == "rapid" and (p[:2] != q[:2]).any()]
    assert {round(p[2], 4) for p in travel[2:]} == {20.0 if retract == "initial" else 2.0}
    for control, post in (("linuxcnc", LinuxCNCPost()), ("fanuc-mill", FanucPost()), ("grbl", GrblPost())):
        assert controller_rules.check(posted(op, post), control) == [], control


def test_grbl_writes_the_expanded_moves_and_fanuc_the_dwell_in_milliseconds():
    op = drill.plan(HOLES, drill.DrillSettings(peck=0.0, dwell=0.25), top=0.0)
    grbl = posted(op, GrblPost())
    assert "G8" not in grbl.replace("G80 ", "")                 # no G81..G89
    assert grbl.count("G01 Z-10.") + grbl.count("Z-10.") >= 4
    fanuc = posted(op, FanucPost())
    assert "G98 G82 X10. Y10. Z-10. R2. P250 F150." in fanuc


def test_the_rules_know_the_cycles():
    base = "%\nG21 G90 G94\nT1 M6\nG43 H1\nS1000 M3\nG00 Z20.\n{}\nG80\nG00 Z20.\nM5\nM30\n%\n"
    assert controller_rules.check(base.format("G98 G81 X1. Y1. Z-5. R2. F100."), "linuxcnc") == []
    rules = {r for r, _, _ in controller_rules.check(base.format("G98 G83 X1. Y1. Z-5. R2. F100."), "linuxcnc")}
    assert rules == {"cycle"}                                    # no Q
    rules = {r for r, _, _ in controller_rules.check(base.format("G98 G81 X1. Y1. Z-5. R-6. F100."), "linuxcnc")}
    assert rules == {"cycle"}                                    # R below the bottom
    found = controller_rules.check(base.format("G98 G81 X1. Y1. Z-5. R2. F100.\nG80\nX5. Y5."), "linuxcnc")
    assert [r for r, _, _ in found] == ["word"]                  # X Y after G80 with no motion mode
    # after a G99 cycle the tool is at the R plane: an XY move at the end before Z is raised
    text = "%\nG21 G90 G94\nT1 M6\nG43 H1\nS1000 M3\nG00 Z20.\nG99 G81 X1. Y1. Z-5. R2. F100.\nG80\nG00 X0. Y0.\nM5\nM30\n%\n"
    assert [r for r, _, _ in controller_rules.check(text, "linuxcnc")] == ["safe-z"]
    assert controller_rules.check(text.replace("G99", "G98"), "linuxcnc") == []   # G98: back at Z20
    assert {r for r, _, _ in controller_rules.check(base.format("G98 G81 X1. Y1. Z-5. R2. F100."), "grbl")} >= {"cycle"}
    fanuc = FanucPost().to_text(Program("holes", [drill.plan(HOLES, drill.DrillSettings(peck=2.0))]))
    assert controller_rules.check(fanuc, "fanuc-mill") == []
    assert [r for r, _, _ in controller_rules.check(fanuc.replace("Q2.", "Q2"), "fanuc-mill")] == ["cycle"]
    dwell = FanucPost().to_text(Program("holes", [drill.plan(HOLES, drill.DrillSettings(peck=0.0, dwell=0.5))]))
    assert [r for r, _, _ in controller_rules.check(dwell.replace("P500", "P0.5"), "fanuc-mill")] == ["cycle"]


def test_the_cycle_must_say_what_the_moves_do():
    op = drill.plan(HOLES, drill.DrillSettings(peck=0.0), top=0.0)
    with pytest.raises(CycleError, match="hole 1 at X10 Y10 is not fed to Z-9"):
        op.replace(cycle=DrillCycle("drill", tuple(HOLES), 20.0, 2.0, -9.0, 150.0))
    with pytest.raises(CycleError, match="a feed move at .* is at none of its holes"):
        op.replace(cycle=DrillCycle("drill", tuple(HOLES[:3]), 20.0, 2.0, -10.0, 150.0))
    with pytest.raises(CycleError, match="peck of 0 mm does not fit a 'peck' cycle"):
        DrillCycle("peck", tuple(HOLES), 20.0, 2.0, -10.0, 150.0).validate()
    with pytest.raises(CycleError, match="must rise in that order"):
        DrillCycle("drill", tuple(HOLES), 1.0, 2.0, -10.0, 150.0).validate()
    with pytest.raises(ProgramError, match="cycle must be a DrillCycle"):
        op.replace(cycle="G81")
    with pytest.raises(drill.DrillError, match="dwell is for holes drilled without pecks"):
        drill.plan(HOLES, drill.DrillSettings(peck=2.0, dwell=1.0))


# ----- cuts measured in the simulation ----------------------------------------------------------

def cut_diameter(result, level):
    """2 sqrt(A / pi) of the cells cut below ``level``."""
    hf = result.heightfield
    area = np.count_nonzero(hf.heights < level) * hf.cell_x * hf.cell_y
    return 2 * math.sqrt(area / math.pi)


def heights_at(result, x, y):
    hf = result.heightfield
    i, j = int((x - hf.x0) / hf.cell_x), int((y - hf.y0) / hf.cell_y)
    return hf.heights[i, j]


def test_drilled_blind_and_through_holes_simulated():
    tool = Tool(4, "drill", 5.0, flute_length=40.0)
    settings = drill.DrillSettings(tool=tool, depth=7.0, peck=2.0)
    part = jobs.kind_of("drill").plan(jobs.Setup(), settings, DrillGeometry(((10.0, 10.0),), 0.0))
    stock = BoxStock(0, 0, -12, 20, 20, 0)
    result = simulate(list(part.operations), stock, cell=0.025)
    assert result.findings == []
    # the tip at Z-7; the cone: depth at radius r is 7 - r / tan(59 deg); full diameter 5 mm at the top
    assert heights_at(result, 10.0125, 10.0125) == pytest.approx(-7.0, abs=0.03)
    point = 2.5 / math.tan(math.radians(59))
    assert cut_diameter(result, -1e-6) == pytest.approx(5.0, abs=0.02)
    assert cut_diameter(result, -7.0 + point - 1e-6) == pytest.approx(5.0, abs=0.02)
    # a through hole in a 6 mm plate (found in a mesh: bottom Z-6): full diameter 0.5 mm below it
    geometry = DrillGeometry(((10.0, 10.0),), 0.0, (5.0,), (-6.0,), (True,), -6.0)
    part = jobs.kind_of("drill").plan(jobs.Setup(), settings, geometry)
    bottom = min(float(op.xyz[:, 2].min()) for op in part.operations)
    assert bottom == pytest.approx(-6.0 - 0.5 - point)
    result = simulate(list(part.operations), BoxStock(0, 0, -6, 20, 20, 0), cell=0.025,
                      fixture_clearance=part.fixture_clearance)
    assert result.findings == []
    assert cut_diameter(result, -6.0 - 1e-6) == pytest.approx(5.0, abs=0.02)   # through at full size


def test_helix_milled_hole_diameter_and_floor():
    settings = drill.DrillSettings(helix=True, mill=Tool(5, "flat", 6.0, flute_length=25.0), helix_pitch=1.5)
    geometry = DrillGeometry(((10.0, 10.0), (30.0, 10.0)), 0.0, (12.0, 4.0), (-5.0, -5.0), (False, False))
    part = jobs.kind_of("drill").plan(jobs.Setup(), settings, geometry)
    names = [op.name for op in part.operations]
    assert names == ["drill", "helix milling"]
    helix = part.operations[1]
    arcs = np.isin(helix.kind, (2, 3))
    # 7 mm from the R plane (Z2) to Z-5 in turns of at most 1.5 mm: 5 turns and the floor's circle
    assert arcs.sum() == 6 and np.all(helix.kind[arcs] == 3)
    assert np.allclose(np.diff(np.concatenate([[2.0], helix.xyz[arcs, 2]])), [-1.4] * 5 + [0.0])
    result = simulate([helix], BoxStock(0, 0, -10, 20, 20, 0), cell=0.02)
    assert result.findings == []
    assert cut_diameter(result, -1e-6) == pytest.approx(12.0, abs=0.02)
    assert cut_diameter(result, -5.0 + 1e-6) == pytest.approx(12.0, abs=0.02)   # the floor flat to the wall
    assert heights_at(result, 10.01, 10.01) == pytest.approx(-5.0, abs=1e-9)
    text = posted(helix, LinuxCNCPost())
    assert text.count("G03") == 6
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=[5]))
    assert kinds.count("ccw") == 6 and points[:, 2].min() == pytest.approx(-5.0)
    assert controller_rules.check(text, "linuxcnc") == []
    with pytest.raises(drill.DrillError, match="not wider than"):
        plan_helix([(0, 0)], [6.0], [-3.0], settings)


def test_spot_pass_and_diameter_filter():
    settings = drill.DrillSettings(spot=True, min_diameter=3.0, max_diameter=6.0)
    geometry = DrillGeometry(tuple(HOLES), 0.0, (2.0, 5.0, 5.0, 8.0))
    part = jobs.kind_of("drill").plan(jobs.Setup(), settings, geometry)
    spot, drilled = part.operations
    assert spot.tool.label == "spot drill" and spot.cycle.bottom_z == pytest.approx(-1.0)
    assert sorted(spot.cycle.holes) == sorted(drilled.cycle.holes) == [(30.0, 10.0), (30.0, 25.0)]
    result = simulate([spot, drilled], BoxStock(0, 0, -15, 40, 35, 0), cell=0.025)
    assert result.findings == []
    # the spot's 118 deg cone 1 mm deep is 2 x 1 x tan(59 deg) = 3.33 mm wide at the top, inside the 5 mm hole
    spot_only = simulate([spot], BoxStock(0, 0, -15, 40, 35, 0), cell=0.025)
    width = 2 * 1.0 * math.tan(math.radians(59))
    assert cut_diameter(spot_only, -1e-6) == pytest.approx(math.sqrt(2) * width, abs=0.03)     # two cones
    with pytest.raises(drill.DrillError, match="no hole is between"):
        jobs.kind_of("drill").plan(jobs.Setup(), drill.DrillSettings(min_diameter=9.0), geometry)


def test_visiting_order_is_short():
    rng = np.random.default_rng(3)
    points = rng.uniform(0, 100, (40, 2))
    order = short_order(points)
    assert sorted(order.tolist()) == list(range(40))
    # against the given order and a lower bound: the tour is at least the minimum spanning tree's length
    distance = np.hypot(*(points[:, None, :] - points[None, :, :]).transpose(2, 0, 1))
    reach, inside, mst = distance[0].copy(), np.zeros(40, bool), 0.0      # Prim's spanning tree
    inside[0] = True
    for _ in range(39):
        k = int(np.argmin(np.where(inside, np.inf, reach)))
        mst += reach[k]
        inside[k] = True
        reach = np.minimum(reach, distance[k])
    assert tour_length(points, order) < 0.4 * tour_length(points, range(40))
    assert tour_length(points, order) < 1.35 * mst
    # points on a line, shuffled: the shortest open tour runs end to end
    line = np.column_stack([rng.permutation(20) * 5.0, np.zeros(20)])
    assert tour_length(line, short_order(line, start=(0, 0))) == pytest.approx(95.0)
