"""SLOT along a circular or general course of travel: PARTIAL_CIRCULAR_PATH, COMPLETE_CIRCULAR_PATH and
GENERAL_PATH, with open, radiused and flat ends.

Our own Part 21 file in the layout of the ISO 14649-11 annex examples: a 120 x 80 x 30 plate with a
10 mm slot on a quarter circle (R20 about X40 Y40, radiused ends) and a 10 mm ring groove (R10 about
X95 Y60) cut by a 10 mm end mill along their centre lines, and a 16 mm L-shaped slot along a polyline,
open where it leaves the plate's edge and radiused at its other end, roughed and finished as the pocket
its outline is.  The expected geometry is computed here from the numbers in the text: closed forms
for the circular slots, and for the L a fine grid of points within half the width of its centre line.
"""
import math
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.simulate import BoxStock, blocking, simulate
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program

STOCK = BoxStock(0, 0, -30, 120, 80, 0)


def slot_file(general_curve="#83", path3_placement="$") -> str:
    return f"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: CURVED SLOTS'),'2;1');
FILE_NAME('slot_paths.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('CURVED SLOTS',#2,(#3),$,$,$);
#2= WORKPLAN('MAIN WORKPLAN',(#60,#61,#62,#63),$,#5,$);
#3= WORKPIECE('PLATE',$,0.01,$,$,#7,());
#4= AXIS2_PLACEMENT_3D('WORKPIECE ORIGIN',#10,#11,#12);
#5= SETUP('SETUP1',#4,#6,(#8));
#6= PLANE('SECURITY PLANE',#9);
#7= BLOCK('PLATE BLOCK',#13,120.000,80.000,30.000);
#8= WORKPIECE_SETUP(#3,#4,$,$,());
#9= AXIS2_PLACEMENT_3D('SECURITY PLANE',#14,#11,#12);
#10= CARTESIAN_POINT('ORIGIN',(0.000,0.000,0.000));
#11= DIRECTION('Z AXIS',(0.000,0.000,1.000));
#12= DIRECTION('X AXIS',(1.000,0.000,0.000));
#13= AXIS2_PLACEMENT_3D('BLOCK CORNER',#15,#11,#12);
#14= CARTESIAN_POINT('SECURITY PLANE',(0.000,0.000,30.000));
#15= CARTESIAN_POINT('BLOCK CORNER',(0.000,0.000,-30.000));
#16= DIRECTION('TILTED',(0.000,0.600,0.800));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(10.000,$,$,25.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(25.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.015,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#27= BIDIRECTIONAL(0.400,.T.,$,.LEFT.,$);
#28= CONTOUR_PARALLEL(0.400,.T.,.CCW.,.CLIMB.);
#29= RADIUSED_SLOT_END_TYPE();
#19= OPEN_SLOT_END_TYPE();
#30= SLOT('ARC SLOT',#3,(#50),#31,#35,#33,#34,(#29,#29));
#31= AXIS2_PLACEMENT_3D('ARC SLOT',#32,#11,#12);
#32= CARTESIAN_POINT('ARC SLOT: CENTRE',(40.000,40.000,0.000));
#33= PARTIAL_CIRCULAR_PATH($,#38,90.000);
#34= SQUARE_U_PROFILE($,#39,$,$,$,$);
#35= PLANE('ARC SLOT DEPTH',#36);
#36= AXIS2_PLACEMENT_3D('ARC SLOT DEPTH',#37,#11,#12);
#37= CARTESIAN_POINT('ARC SLOT DEPTH',(0.000,0.000,-4.000));
#38= TOLERANCED_LENGTH_MEASURE(20.000,#90);
#39= TOLERANCED_LENGTH_MEASURE(10.000,#90);
#40= SLOT('RING GROOVE',#3,(#51),#41,#45,#43,#34,());
#41= AXIS2_PLACEMENT_3D('RING GROOVE',#42,#11,#12);
#42= CARTESIAN_POINT('RING GROOVE: CENTRE',(95.000,60.000,0.000));
#43= COMPLETE_CIRCULAR_PATH({path3_placement},#39);
#44= AXIS2_PLACEMENT_3D('TILTED PATH',#10,#16,$);
#45= PLANE('RING GROOVE DEPTH',#46);
#46= AXIS2_PLACEMENT_3D('RING GROOVE DEPTH',#47,#11,#12);
#47= CARTESIAN_POINT('RING GROOVE DEPTH',(0.000,0.000,-3.000));
#70= SLOT('L SLOT',#3,(#52,#53),#71,#75,#73,#74,(#19,#29));
#71= AXIS2_PLACEMENT_3D('L SLOT',#72,#11,#12);
#72= CARTESIAN_POINT('L SLOT: START',(80.000,0.000,0.000));
#73= GENERAL_PATH($,{general_curve});
#74= SQUARE_U_PROFILE($,#78,$,90.000,$,90.000);
#75= PLANE('L SLOT DEPTH',#76);
#76= AXIS2_PLACEMENT_3D('L SLOT DEPTH',#77,#11,#12);
#77= CARTESIAN_POINT('L SLOT DEPTH',(0.000,0.000,-5.000));
#78= TOLERANCED_LENGTH_MEASURE(16.000,#90);
#83= POLYLINE('L SLOT CENTRE LINE',(#84,#85,#86));
#84= CARTESIAN_POINT('L1',(0.000,0.000,0.000));
#85= CARTESIAN_POINT('L2',(0.000,20.000,0.000));
#86= CARTESIAN_POINT('L3',(25.000,20.000,0.000));
#87= B_SPLINE_CURVE_WITH_KNOTS('L SPLINE',2,(#84,#85,#86),.UNSPECIFIED.,.F.,.F.,(3,3),(0.,1.),.UNSPECIFIED.);
#50= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'MILL ARC SLOT',5.000,$,#22,#24,#25,$,$,$,$,2.000,$,$,$);
#51= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'MILL RING GROOVE',5.000,$,#22,#24,#25,$,$,$,$,3.000,$,$,$);
#52= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH L SLOT',5.000,$,#22,#24,#25,$,$,$,#27,2.500,$,0.500,0.200);
#53= BOTTOM_AND_SIDE_FINISH_MILLING($,$,'FINISH L SLOT',5.000,$,#22,#24,#25,$,$,$,#28,2.500,$,$,$);
#60= MACHINING_WORKINGSTEP('WS ARC SLOT',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS RING GROOVE',#6,#40,#51,$);
#62= MACHINING_WORKINGSTEP('WS ROUGH L SLOT',#6,#70,#52,$);
#63= MACHINING_WORKINGSTEP('WS FINISH L SLOT',#6,#70,#53,$);
#90= PLUS_MINUS_VALUE(0.010,0.010,3);
ENDSEC;
END-ISO-10303-21;
"""


TEXT = slot_file()


def numbers(ident):
    line = re.search(rf"^#{ident}= .*$", TEXT, re.MULTILINE).group(0)
    return np.array([float(v) for v in re.search(r"\(([-\d.,]+)\)\);$", line).group(1).split(",")])


def measure(ident):
    return float(re.search(rf"^#{ident}= TOLERANCED_LENGTH_MEASURE\(([\d.]+),", TEXT, re.MULTILINE).group(1))


def l_slot_line():
    start = numbers(72)[:2]
    return np.array([start + numbers(i)[:2] for i in (84, 85, 86)])


def within(points, line, half):
    """Which points lie within ``half`` of the polyline (round joins and caps)."""
    best = np.full(len(points), np.inf)
    for a, b in zip(line[:-1], line[1:]):
        t = np.clip(((points - a) @ (b - a)) / ((b - a) @ (b - a)), 0, 1)
        best = np.minimum(best, np.linalg.norm(points - (a + t[:, None] * (b - a)), axis=1))
    return best <= half


@pytest.fixture(scope="module")
def slots():
    loaded = load_workplan(TEXT)
    return loaded, to_program(loaded)


def test_the_arc_slot_is_cut_on_its_circle(slots):
    _, program = slots
    centre, radius = numbers(32)[:2], measure(38)
    op = program.operations[0]
    cuts = op.xyz[op.kind == FEED]
    assert np.allclose(np.linalg.norm(cuts[:, :2] - centre, axis=1), radius, atol=1e-6)
    angles = np.degrees(np.arctan2(cuts[:, 1] - centre[1], cuts[:, 0] - centre[0]))
    assert angles.min() == pytest.approx(0.0, abs=1e-6) and angles.max() == pytest.approx(90.0, abs=1e-6)
    assert cuts[:, 2].min() == pytest.approx(numbers(37)[2])


def test_the_ring_groove_goes_round(slots):
    _, program = slots
    centre, radius = numbers(42)[:2], measure(39)
    op = program.operations[1]
    cuts = op.xyz[op.kind == FEED]
    assert np.allclose(np.linalg.norm(cuts[:, :2] - centre, axis=1), radius, atol=1e-6)
    angles = np.arctan2(cuts[:, 1] - centre[1], cuts[:, 0] - centre[0])
    assert np.ptp(np.cos(angles)) > 1.99 and np.ptp(np.sin(angles)) > 1.99     # all the way round
    assert cuts[:, 2].min() == pytest.approx(numbers(47)[2])


def test_the_l_slot_reaches_its_walls_and_runs_out_of_the_plate(slots):
    _, program = slots
    line, half, r = l_slot_line(), measure(78) / 2, 5.0
    rough, finish = program.operations[2:]
    floor = finish.xyz[(finish.kind == FEED)]
    floor = floor[floor[:, 1] >= 0]                                            # on the plate (the open end runs out)
    rim = np.column_stack([np.cos(np.linspace(0, 2 * np.pi, 72)), np.sin(np.linspace(0, 2 * np.pi, 72))]) * r
    edge = (floor[:, None, :2] + rim[None, :, :]).reshape(-1, 2)              # the tool's rim at every point
    assert within(edge, line, half + 0.01).all()                               # never past the walls
    assert not within(edge, line, half - 0.01).all()                           # and touching them
    assert rough.xyz[rough.kind == FEED][:, 1].min() <= -r                     # open end: out past the edge
    assert finish.xyz[finish.kind == FEED][:, 2].min() == pytest.approx(numbers(77)[2])


def test_simulated_slots_have_their_volume(slots):
    _, program = slots
    result = simulate(program, STOCK, cell=0.2)
    assert blocking(result.findings) == []
    w1, r1 = measure(39), measure(38)
    arc = (math.pi / 2) * ((r1 + w1 / 2) ** 2 - (r1 - w1 / 2) ** 2) / 2 + math.pi * (w1 / 2) ** 2
    ring = math.pi * ((measure(39) + w1 / 2) ** 2 - (measure(39) - w1 / 2) ** 2)
    step = 0.05
    xs, ys = np.meshgrid(np.arange(60, 120, step) + step / 2, np.arange(0, 50, step) + step / 2)
    grid = np.column_stack([xs.ravel(), ys.ravel()])
    l_area = within(grid, l_slot_line(), measure(78) / 2).sum() * step * step
    expected = arc * -numbers(37)[2] + ring * -numbers(47)[2] + l_area * -numbers(77)[2]
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=0.01)


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_accepts_the_curved_slots(slots):
    _, program = slots
    kinds, points, _ = rs274.motion_endpoints(rs274.run(post.milling_post("linuxcnc").to_text(program)))
    assert points[np.array(kinds) == "feed"][:, 2].min() == pytest.approx(-5.0, abs=1e-3)


def test_a_b_spline_centre_line_is_followed():
    """The L's corner points as the control points of a quadratic B-spline (knots 0,0,0,1,1,1): a Bezier
    curve, B(t) = (1-t)^2 P0 + 2t(1-t) P1 + t^2 P2, evaluated here in closed form."""
    loaded = load_workplan(slot_file(general_curve="#87"))
    assert [s.id for s in loaded.workingsteps] == [60, 61, 62, 63] and loaded.warnings == ()
    p0, p1, p2 = l_slot_line()
    t = np.linspace(0, 1, 20001)[:, None]
    bezier = (1 - t) ** 2 * p0 + 2 * t * (1 - t) * p1 + t ** 2 * p2
    sampled = loaded.workingsteps[2].its_feature.centreline()
    assert np.allclose(sampled[[0, -1]], [p0, p2])
    gap = np.min(np.linalg.norm(sampled[:, None, :] - bezier[None, :, :], axis=2), axis=1)
    assert gap.max() < 0.002                                  # on the curve (the closed form sampled 0.002 mm apart)
    finish = to_program(loaded).operations[3]
    floor = finish.xyz[finish.kind == FEED]
    floor = floor[floor[:, 1] >= 0]
    rim = np.column_stack([np.cos(np.linspace(0, 2 * np.pi, 72)), np.sin(np.linspace(0, 2 * np.pi, 72))]) * 5.0
    edge = (floor[:, None, :2] + rim[None, :, :]).reshape(-1, 2)
    assert within(edge, bezier[::20], measure(78) / 2 + 0.01).all()


def test_paths_not_machined_are_named():
    rational = slot_file(general_curve="#88").replace(
        "#90= PLUS_MINUS_VALUE", "#88=(BOUNDED_CURVE()B_SPLINE_CURVE(2,(#84,#85,#86),.UNSPECIFIED.,.F.,.F.)"
        "B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()"
        "RATIONAL_B_SPLINE_CURVE((1.,0.7,1.))REPRESENTATION_ITEM('L ARC'));\n#90= PLUS_MINUS_VALUE")
    spline = load_workplan(rational)
    assert [s.id for s in spline.workingsteps] == [60, 61]
    assert any("'WS ROUGH L SLOT' skipped: (BOUNDED_CURVE B_SPLINE_CURVE B_SPLINE_CURVE_WITH_KNOTS CURVE "
               "GEOMETRIC_REPRESENTATION_ITEM RATIONAL_B_SPLINE_CURVE REPRESENTATION_ITEM) #88 is not supported" in w
               for w in spline.warnings)
    tilted = load_workplan(slot_file(path3_placement="#44"))
    assert any("'WS RING GROOVE' skipped: COMPLETE_CIRCULAR_PATH #43 is not supported" in w for w in tilted.warnings)
