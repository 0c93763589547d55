"""CONTOUR_BIDIRECTIONAL and BIDIRECTIONAL_CONTOUR (ISO 14649-11 two5d strategies): zigzag strokes along
feed_direction stepping to stepover_direction, and one contour pass along the boundary, before the
strokes (CONTOUR_BIDIRECTIONAL) or after them (BIDIRECTIONAL_CONTOUR), turning rotation_direction or
as spiral_cutmode says.

Our own Part 21 file in the layout of the ISO 14649-11 annex examples: a 120 x 80 x 30 plate with two
60 x 30 pockets (corner radius 8), 6 deep, roughed with a 10 mm end mill, one with each strategy; and NIST's
ex1 with its planar face's strategy written as CONTOUR_BIDIRECTIONAL.  The numbers the tests expect are read from the text.
"""
import math
import os
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.simulate import BoxStock, blocking, simulate
from kezuri.toolpath.operations.stepnc.process import ContourBidirectional
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program

STOCK = BoxStock(0, 0, -30, 120, 80, 0)

TEXT = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: CONTOUR_BIDIRECTIONAL'),'2;1');
FILE_NAME('contour_bidirectional.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('STRATEGIES',#2,(#3),$,$,$);
#2= WORKPLAN('MAIN WORKPLAN',(#60,#61),$,#5,$);
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
#16= DIRECTION('Y AXIS',(0.000,1.000,0.000));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(10.000,$,$,25.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(25.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.020,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#26= CONTOUR_BIDIRECTIONAL(0.400,.T.,#12,.LEFT.,.CCW.,$);
#27= BIDIRECTIONAL_CONTOUR(0.500,.T.,#16,.RIGHT.,$,.CONVENTIONAL.);
#30= CLOSED_POCKET('POCKET1',#3,(#50),#31,#33,(),$,#36,$,#37,#38);
#31= AXIS2_PLACEMENT_3D('POCKET1',#32,#11,#12);
#32= CARTESIAN_POINT('POCKET1: LOCATION ',(35.000,40.000,0.000));
#33= PLANE('POCKET1 DEPTH',#34);
#34= AXIS2_PLACEMENT_3D('POCKET1 DEPTH',#35,#11,#12);
#35= CARTESIAN_POINT('POCKET1: DEPTH ',(0.000,0.000,-6.000));
#36= PLANAR_POCKET_BOTTOM_CONDITION();
#37= TOLERANCED_LENGTH_MEASURE(8.000,#90);
#38= RECTANGULAR_CLOSED_PROFILE($,#39,#49);
#39= TOLERANCED_LENGTH_MEASURE(30.000,#90);
#49= TOLERANCED_LENGTH_MEASURE(60.000,#90);
#40= CLOSED_POCKET('POCKET2',#3,(#51),#41,#33,(),$,#36,$,#37,#48);
#41= AXIS2_PLACEMENT_3D('POCKET2',#42,#11,#16);
#42= CARTESIAN_POINT('POCKET2: LOCATION ',(95.000,40.000,0.000));
#48= RECTANGULAR_CLOSED_PROFILE($,#39,#49);
#50= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET1',5.000,$,#22,#24,#25,$,$,$,#26,3.000,$,$,$);
#51= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET2',5.000,$,#22,#24,#25,$,$,$,#27,3.000,$,$,$);
#60= MACHINING_WORKINGSTEP('WS ROUGH POCKET1',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS ROUGH POCKET2',#6,#40,#51,$);
#90= PLUS_MINUS_VALUE(0.010,0.010,3);
ENDSEC;
END-ISO-10303-21;
"""


def numbers(ident):
    line = re.search(rf"^#{ident}= .*$", TEXT, re.MULTILINE).group(0)
    return np.array([float(v) for v in re.search(r"\(([-\d.,]+)\)\);$", line).group(1).split(",")])


def value(ident):
    return float(re.search(rf"^#{ident}= TOLERANCED_LENGTH_MEASURE\(([\d.]+),", TEXT, re.MULTILINE).group(1))


@pytest.fixture(scope="module")
def planned():
    loaded = load_workplan(TEXT)
    return loaded, to_program(loaded)


def layer(op, z):
    """The feed moves of one layer (at height z), in order."""
    at = (op.kind == FEED) & np.isclose(op.xyz[:, 2], z)
    return op.xyz[at][:, :2]


def test_strategies_are_read(planned):
    loaded, _ = planned
    first, second = (step.its_operation.its_machining_strategy for step in loaded.workingsteps)
    assert isinstance(first, ContourBidirectional) and first.contour_first and first.rotation_direction == "CCW"
    assert isinstance(second, ContourBidirectional) and not second.contour_first
    assert second.spiral_cutmode == "CONVENTIONAL" and second.stepover_direction == "RIGHT"


def test_contour_first_then_strokes_along_the_feed_direction(planned):
    _, program = planned
    centre, length, width, r = numbers(32)[:2], value(49), value(39), 5.0
    points = layer(program.operations[0], -3.0)
    half = np.array([length / 2 - r, width / 2 - r])                  # the tool centre's reach
    offset = np.abs(points - centre)
    closes = [k for k in range(1, len(points)) if np.allclose(points[k], points[0], atol=1e-6)]
    ring_end = closes[0] + 1                                         # the contour comes first: a closed loop
    ring = points[:ring_end]
    assert ring_end > 8
    reach = np.abs(ring - centre)
    corner = (reach[:, 0] > half[0] - 3.0 + 1e-6) & (reach[:, 1] > half[1] - 3.0 + 1e-6)   # R8 - r = 3
    sides = np.isclose(reach[:, 0], half[0], atol=1e-6) | np.isclose(reach[:, 1], half[1], atol=1e-6)
    assert np.all(corner | sides)                                    # every ring point on the reach's outline
    x, y = ring[:, 0], ring[:, 1]
    assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0       # counter-clockwise (.CCW.)
    assert offset.max(axis=0) == pytest.approx(half, abs=1e-6)
    strokes = points[ring_end:]
    along = np.diff(strokes, axis=0)
    rows = sorted({round(v, 6) for v in strokes[np.r_[np.abs(along[:, 1]) < 1e-9, False], 1]})
    step = np.diff(rows)
    assert np.all(step <= 10.0 * (1 - 0.4) + 1e-6)                   # overlap 0.4 of the diameter
    assert np.abs(along[:, 0]).sum() > np.abs(along[:, 1]).sum()    # feed_direction X


def test_strokes_then_contour_conventional(planned):
    _, program = planned
    centre, r = numbers(42)[:2], 5.0
    points = layer(program.operations[1], -3.0)
    along = np.diff(points, axis=0)
    # POCKET2's x axis is the machine's Y: 60 along Y, 30 along X; feed_direction #16 is the pocket's y axis
    # (ISO 14649 gives it in the feature's coordinates): the machine's -X
    assert np.abs(points - centre).max(axis=0) == pytest.approx([15.0 - r, 30.0 - r], abs=1e-6)
    first_stroke = along[0]
    assert abs(first_stroke[0]) > abs(first_stroke[1])
    # the last loop is the contour, conventional with a clockwise spindle: clockwise
    start = max(k for k in range(len(points) - 1) if np.allclose(points[k], points[-1], atol=1e-6))
    tail = points[start:]
    assert len(tail) > 8
    x, y = tail[:, 0], tail[:, 1]
    assert 0.5 * np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]) < 0


def test_simulated_pockets_have_their_volume(planned):
    _, program = planned
    result = simulate(program, STOCK, cell=0.2)
    assert blocking(result.findings) == []
    one = (value(49) * value(39) - (4 - math.pi) * value(37) ** 2) * 6.0
    assert result.removed_volume_mm3 == pytest.approx(2 * one, rel=0.01)


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_accepts_them(planned):
    _, program = planned
    kinds, points, _ = rs274.motion_endpoints(rs274.run(post.milling_post("linuxcnc").to_text(program)))
    assert points[np.array(kinds) == "feed"][:, 2].min() == pytest.approx(-6.0, abs=1e-3)


def test_a_planar_face_is_zigzagged_without_a_contour_pass():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "iso14649", "ex1.stp")
    with open(path, encoding="latin-1") as stream:
        text = stream.read()
    contour = text.replace("#42= BIDIRECTIONAL_MILLING(0.05, .T., #43, .LEFT., $);",
                           "#42= CONTOUR_BIDIRECTIONAL(0.05, .T., #43, .LEFT., $, $);")
    assert contour != text
    plain, other = to_program(load_workplan(text)), to_program(load_workplan(contour))
    assert np.array_equal(plain.operations[0].xyz, other.operations[0].xyz)
    assert any("no contour pass on planar face #16" in note for note in other.notes)
