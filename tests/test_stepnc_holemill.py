"""Hole milling: BOTTOM_AND_SIDE_ROUGH/FINISH_MILLING on a ROUND_HOLE, by helical interpolation.

Our own Part 21 file, laid out as the ISO 14649-11 annex examples are: a 120 x 80 x 30 plate, a
30 mm blind bore (12 deep, flat bottom) roughed and finished with a 10 mm end mill, and a 16 mm
through hole finished with it.  The tests read the diameters, centres and depths from the text.
"""
import itertools
import math
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, RAPID
from kezuri.toolpath.simulate import BoxStock, simulate
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program


def bore_file(tool="#22", bore_diameter=30.0) -> str:
    return f"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: HOLE MILLING'),'2;1');
FILE_NAME('holemill.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('BORES',#2,(#3),$,$,$);
#2= WORKPLAN('MAIN WORKPLAN',(#60,#61,#62),$,#5,$);
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
#14= CARTESIAN_POINT('SECURITY PLANE',(0.000,0.000,50.000));
#15= CARTESIAN_POINT('BLOCK CORNER',(0.000,0.000,-30.000));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(10.000,$,$,35.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(35.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.015,.TCP.,$,-120.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#27= CONTOUR_PARALLEL(0.400,.T.,.CCW.,.CLIMB.);
#120= TWIST_DRILL(#121,2,.RIGHT.,.F.,$);
#121= MILLING_TOOL_DIMENSION(10.000,31.000,$,40.000,$,$,$);
#122= MILLING_CUTTING_TOOL('DRILL 10MM',#120,(#123),$,$,$);
#123= CUTTING_COMPONENT(40.000,$,$,$,$);
#30= ROUND_HOLE('BORE1',#3,(#50,#51),#31,#35,{bore_diameter:.3f},$,#38);
#31= AXIS2_PLACEMENT_3D('BORE1',#32,#11,#12);
#32= CARTESIAN_POINT('BORE1',(40.000,40.000,0.000));
#35= PLANE('BORE1 DEPTH',#36);
#36= AXIS2_PLACEMENT_3D('BORE1 DEPTH',#37,#11,#12);
#37= CARTESIAN_POINT('BORE1 DEPTH',(0.000,0.000,-12.000));
#38= FLAT_HOLE_BOTTOM();
#40= ROUND_HOLE('HOLE2',#3,(#52),#41,#45,16.000,$,#48);
#41= AXIS2_PLACEMENT_3D('HOLE2',#42,#11,#12);
#42= CARTESIAN_POINT('HOLE2',(90.000,40.000,0.000));
#45= PLANE('HOLE2 DEPTH',#46);
#46= AXIS2_PLACEMENT_3D('HOLE2 DEPTH',#47,#11,#12);
#47= CARTESIAN_POINT('HOLE2 DEPTH',(0.000,0.000,-30.000));
#48= THROUGH_BOTTOM_CONDITION();
#50= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH BORE1',5.000,$,{tool},#24,#25,$,$,$,#27,4.000,$,0.500,0.200);
#51= BOTTOM_AND_SIDE_FINISH_MILLING($,$,'FINISH BORE1',5.000,$,#22,#24,#25,$,$,$,#27,4.000,$,$,$);
#52= BOTTOM_AND_SIDE_FINISH_MILLING($,$,'FINISH HOLE2',5.000,$,#22,#24,#25,$,$,$,#27,5.000,$,$,$);
#60= MACHINING_WORKINGSTEP('WS ROUGH BORE1',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS FINISH BORE1',#6,#30,#51,$);
#62= MACHINING_WORKINGSTEP('WS FINISH HOLE2',#6,#40,#52,$);
ENDSEC;
END-ISO-10303-21;
"""


def hole_from_text(text, name):
    """(centre xy, diameter, depth) of a ROUND_HOLE, read with regular expressions."""
    hole = re.search(rf"^#\d+= ROUND_HOLE\('{name}',#\d+,\([^)]*\),#(\d+),#(\d+),([\d.]+),", text, re.MULTILINE)
    def point_of(placement):
        ref = re.search(rf"^#{placement}= AXIS2_PLACEMENT_3D\('[^']*',#(\d+)", text, re.MULTILINE).group(1)
        values = re.search(rf"^#{ref}= CARTESIAN_POINT\('[^']*',\(([^)]*)\)\)", text, re.MULTILINE).group(1)
        return np.array([float(v) for v in values.split(",")])
    depth_plane = re.search(rf"^#{hole.group(2)}= PLANE\('[^']*',#(\d+)\)", text, re.MULTILINE).group(1)
    return point_of(hole.group(1))[:2], float(hole.group(3)), -point_of(depth_plane)[2]


def tool_diameter_from_text(text):
    return float(re.search(r"^#21= MILLING_TOOL_DIMENSION\(([\d.]+)", text, re.MULTILINE).group(1))


def arc_radii(op):
    """(radius, centre) of every arc move: distance from its start point to its centre."""
    arcs = np.flatnonzero((op.kind == ARC_CW) | (op.kind == ARC_CCW))
    starts = op.start_points()[arcs]
    return np.linalg.norm(starts[:, :2] - op.center[arcs, :2], axis=1), op.center[arcs, :2], op.xyz[arcs]


@pytest.fixture(scope="module")
def bores():
    text = bore_file()
    loaded = load_workplan(text)
    return text, loaded, to_program(loaded)


def test_circles_reach_the_diameter(bores):
    text, loaded, program = bores
    r = tool_diameter_from_text(text) / 2
    (rough, finish, through) = program.operations
    centre1, d1, depth1 = hole_from_text(text, "BORE1")
    centre2, d2, depth2 = hole_from_text(text, "HOLE2")
    radii, centres, ends = arc_radii(finish)
    np.testing.assert_allclose(centres, np.tile(centre1, (len(centres), 1)))
    assert radii.max() == pytest.approx(d1 / 2 - r, abs=1e-9)                  # the wall, exactly
    assert ends[:, 2].min() == pytest.approx(-depth1)
    radii, centres, ends = arc_radii(rough)
    assert radii.max() == pytest.approx(d1 / 2 - r - 0.5, abs=1e-9)            # allowance_side 0.5
    assert radii.min() <= r                                                     # no core left
    assert ends[:, 2].min() == pytest.approx(-depth1 + 0.2)                     # allowance_bottom 0.2
    radii, centres, ends = arc_radii(through)
    assert np.allclose(radii, d2 / 2 - r) and np.allclose(centres, centre2)     # one circle: helical interpolation
    assert ends[:, 2].min() == pytest.approx(-depth2 - 1.0)                     # 1 mm through the bottom
    # finishing after roughing: above the rough floor only the wall circle
    radii, _, ends = arc_radii(finish)
    assert np.allclose(radii[ends[:, 2] > -depth1 + 0.2 + 1e-9], d1 / 2 - r)


def test_simulated_bores_have_their_volume_and_no_findings(bores):
    text, loaded, program = bores
    centre1, d1, depth1 = hole_from_text(text, "BORE1")
    centre2, d2, depth2 = hole_from_text(text, "HOLE2")
    from kezuri.toolpath.operations.stepnc.solids import fixture_clearance
    clearance = fixture_clearance(loaded)
    assert clearance == pytest.approx(1.01)         # the 1 mm a milled through hole goes below its bottom
    result = simulate(program, BoxStock(0, 0, -30, 120, 80, 0), cell=0.2, fixture_clearance=clearance)
    assert result.findings == []
    expected = math.pi * (d1 / 2) ** 2 * depth1 + math.pi * (d2 / 2) ** 2 * min(depth2, 30.0)
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=0.015)


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_runs_the_helices_about_the_hole_centres(bores):
    text, _, program = bores
    calls = rs274.run(post.milling_post("linuxcnc").to_text(program))
    arcs = [[float(v) for v in args] for name, args in calls if name == "ARC_FEED"]
    assert len(arcs) == sum(int(np.count_nonzero((op.kind == ARC_CW) | (op.kind == ARC_CCW)))
                            for op in program.operations)
    centres = {tuple(np.round(hole_from_text(text, name)[0], 3)) for name in ("BORE1", "HOLE2")}
    assert {(round(a[2], 3), round(a[3], 3)) for a in arcs} == centres        # ARC_FEED(x, y, cx, cy, ...)
    assert all(a[4] > 0 for a in arcs)                                          # CCW (CONTOUR_PARALLEL .CCW.)


def test_every_order_is_safe(bores):
    _, loaded, _ = bores
    ids = [step.id for step in loaded.workingsteps]
    for order in itertools.permutations(ids):
        result = simulate(to_program(loaded, order=list(order)), BoxStock(0, 0, -30, 120, 80, 0), cell=0.4)
        assert [f for f in result.findings if f.kind == "rapid_in_material"] == [], order


def test_hole_milling_that_cannot_be_done_is_skipped_with_the_reason():
    program = to_program(load_workplan(bore_file(tool="#122")))        # roughing with a twist drill
    assert [op.source_id for op in program.operations] == [61, 62]
    assert any("workingstep #60 'WS ROUGH BORE1' skipped: a twist drill cannot mill hole #30" in note
               for note in program.notes)
    program = to_program(load_workplan(bore_file(bore_diameter=10.5)))  # 0.25 mm to interpolate when finishing
    assert [op.source_id for op in program.operations] == [61, 62]
    assert sum("does not fit in the 10.5 mm hole #30" in note for note in program.notes) == 1   # roughing (0.5)
    assert arc_radii(program.operations[0])[0] == pytest.approx(0.25)
    program = to_program(load_workplan(bore_file(bore_diameter=10.0)))  # no room at all
    assert [op.source_id for op in program.operations] == [62]
    assert sum("does not fit in the 10 mm hole #30" in note for note in program.notes) == 2
    assert not [op for op in program.operations if (op.kind == RAPID).all()]
