"""The double-placement case decided by the holes drilled from a pocket's floor.

Our own Part 21 file, no workpiece BLOCK to check against: POCKET1's placement is its corner
(X50 Y30) and its RECTANGULAR_CLOSED_PROFILE's placement repeats its absolute centre (X70 Y40), as
the generators of issue 19 write it.  ISO 14649 composes the two (centre X120 Y70); the two holes that
start on the pocket's floor (Z -10) lie in the pocket only when the profile's placement is read as
absolute, so that reading is taken, with a warning naming the pocket and the holes.  With the holes
moved into the composed pocket, the composed reading stands and nothing is said.
"""
import re

import numpy as np
import pytest

from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.simulate import BoxStock, blocking, simulate
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program


def pocket_file(hole_a=(65.0, 35.0), hole_b=(75.0, 45.0)) -> str:
    return f"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: POCKET FLOOR CLUE'),'2;1');
FILE_NAME('floor_clue.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('FLOOR CLUE',#2,(#3),$,$,$);
#2= WORKPLAN('MAIN WORKPLAN',(#60,#61,#62),$,#5,$);
#3= WORKPIECE('PLATE',$,0.01,$,$,$,());
#4= AXIS2_PLACEMENT_3D('WORKPIECE ORIGIN',#10,#11,#12);
#5= SETUP('SETUP1',#4,#6,(#8));
#6= PLANE('SECURITY PLANE',#9);
#8= WORKPIECE_SETUP(#3,#4,$,$,());
#9= AXIS2_PLACEMENT_3D('SECURITY PLANE',#14,#11,#12);
#10= CARTESIAN_POINT('ORIGIN',(0.000,0.000,0.000));
#11= DIRECTION('Z AXIS',(0.000,0.000,1.000));
#12= DIRECTION('X AXIS',(1.000,0.000,0.000));
#14= CARTESIAN_POINT('SECURITY PLANE',(0.000,0.000,30.000));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(10.000,$,$,25.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(25.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.015,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#26= TWIST_DRILL(#27,2,.RIGHT.,.F.,$);
#27= MILLING_TOOL_DIMENSION(5.000,31.000,$,30.000,$,$,$);
#28= MILLING_CUTTING_TOOL('DRILL 5MM',#26,(#23),$,$,$);
#29= MILLING_TECHNOLOGY(0.002,.TCP.,$,-50.000,$,.F.,.F.,.F.,$);
#30= CLOSED_POCKET('POCKET1',#3,(#50),#31,#33,(),$,#36,$,#37,#38);
#31= AXIS2_PLACEMENT_3D('POCKET1',#32,#11,#12);
#32= CARTESIAN_POINT('POCKET1: CORNER',(50.000,30.000,0.000));
#33= PLANE('POCKET1 DEPTH',#34);
#34= AXIS2_PLACEMENT_3D('POCKET1 DEPTH',#35,#11,#12);
#35= CARTESIAN_POINT('POCKET1 DEPTH',(0.000,0.000,-10.000));
#36= PLANAR_POCKET_BOTTOM_CONDITION();
#37= TOLERANCED_LENGTH_MEASURE(5.000,#90);
#38= RECTANGULAR_CLOSED_PROFILE(#39,#41,#42);
#39= AXIS2_PLACEMENT_3D('POCKET1 PROFILE',#40,#11,#12);
#40= CARTESIAN_POINT('POCKET1: CENTRE',(70.000,40.000,0.000));
#41= TOLERANCED_LENGTH_MEASURE(20.000,#90);
#42= TOLERANCED_LENGTH_MEASURE(40.000,#90);
#43= ROUND_HOLE('HOLE A',#3,(#51),#44,#46,#49,$,#48);
#44= AXIS2_PLACEMENT_3D('HOLE A',#45,#11,#12);
#45= CARTESIAN_POINT('HOLE A',({hole_a[0]:.3f},{hole_a[1]:.3f},-10.000));
#46= PLANE('HOLES DEPTH',#47);
#47= AXIS2_PLACEMENT_3D('HOLES DEPTH',#57,#11,#12);
#57= CARTESIAN_POINT('HOLES DEPTH',(0.000,0.000,-5.000));
#48= FLAT_HOLE_BOTTOM();
#49= TOLERANCED_LENGTH_MEASURE(5.000,#90);
#53= ROUND_HOLE('HOLE B',#3,(#52),#54,#46,#49,$,#48);
#54= AXIS2_PLACEMENT_3D('HOLE B',#55,#11,#12);
#55= CARTESIAN_POINT('HOLE B',({hole_b[0]:.3f},{hole_b[1]:.3f},-10.000));
#50= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'MILL POCKET1',5.000,$,#22,#24,#25,$,$,$,$,5.000,$,$,$);
#51= DRILLING($,$,'DRILL HOLE A',5.000,$,#28,#29,#25,$,$,$,$,$,$);
#52= DRILLING($,$,'DRILL HOLE B',5.000,$,#28,#29,#25,$,$,$,$,$,$);
#60= MACHINING_WORKINGSTEP('WS MILL POCKET1',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS DRILL HOLE A',#6,#43,#51,$);
#62= MACHINING_WORKINGSTEP('WS DRILL HOLE B',#6,#53,#52,$);
#90= PLUS_MINUS_VALUE(0.010,0.010,3);
ENDSEC;
END-ISO-10303-21;
"""


def point(text, name):
    found = re.search(rf"CARTESIAN_POINT\('{name}',\(([-\d.,]+)\)\)", text)
    return np.array([float(v) for v in found.group(1).split(",")])


def test_holes_in_the_floor_decide_the_absolute_reading():
    text = pocket_file()
    loaded = load_workplan(text)
    program = to_program(loaded)
    centre = point(text, "POCKET1: CENTRE")[:2]              # the profile's placement, read as absolute
    cuts = program.operations[0].xyz[program.operations[0].kind == FEED]
    assert cuts[:, :2].min(axis=0) == pytest.approx(centre - [20 - 5, 10 - 5], abs=1e-6)
    assert cuts[:, :2].max(axis=0) == pytest.approx(centre + [20 - 5, 10 - 5], abs=1e-6)
    warning = [w for w in loaded.warnings if w.startswith("#30 CLOSED_POCKET 'POCKET1': the holes")]
    assert len(warning) == 1 and "#43 at X65 Y35" in warning[0] and "#53 at X75 Y45" in warning[0]
    assert "cut at X70 Y40" in warning[0]
    # the holes' drills start inside the pocket: nothing to drill through above its floor
    stock = BoxStock(0, 0, -30, 160, 100, 0)
    assert blocking(simulate(program, stock, cell=0.5).findings) == []


def test_holes_in_the_composed_pocket_keep_iso_14649_s_reading():
    text = pocket_file(hole_a=(115.0, 65.0), hole_b=(125.0, 75.0))
    loaded = load_workplan(text)
    program = to_program(loaded)
    composed = point(text, "POCKET1: CORNER")[:2] + point(text, "POCKET1: CENTRE")[:2]
    cuts = program.operations[0].xyz[program.operations[0].kind == FEED]
    assert (cuts[:, :2].min(axis=0) + cuts[:, :2].max(axis=0)) / 2 == pytest.approx(composed, abs=1e-6)
    assert not any("CLOSED_POCKET" in w for w in loaded.warnings)
