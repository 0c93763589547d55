"""SLOT with a SQUARE_U_PROFILE along a LINEAR_PATH, closed (radiused, flat) and open ends.

Our own Part 21 file in the layout of the ISO 14649-11 annex examples: a 120 x 80 x 30 plate, a
10 mm slot with radiused ends (X 10..60 at Y 20) cut by a 10 mm end mill along its centre line, and a 16 mm slot open at
both ends across the plate, roughed and finished as the pocket its outline is.  The tests read the
slots' positions, widths and depths from the text.
"""
import itertools
import math
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.simulate import BoxStock, simulate
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program

STOCK = BoxStock(0, 0, -30, 120, 80, 0)


def slot_file(first_end="#39", second_end="#39", open_end="#49") -> str:
    return f"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: SLOTS'),'2;1');
FILE_NAME('slots.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('SLOTS',#2,(#3),$,$,$);
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
#16= DIRECTION('Y AXIS',(0.000,1.000,0.000));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(10.000,$,$,35.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(35.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.012,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#26= PLUNGE_RAMP($,10.000);
#27= BIDIRECTIONAL(0.400,.T.,$,.LEFT.,$);
#28= CONTOUR_PARALLEL(0.400,.T.,.CCW.,.CLIMB.);
#30= SLOT('SLOT1',#3,(#50),#31,#35,#33,#34,({first_end},{second_end}));
#31= AXIS2_PLACEMENT_3D('SLOT1',#32,#11,#12);
#32= CARTESIAN_POINT('SLOT1',(10.000,20.000,0.000));
#33= LINEAR_PATH(#4,50.000,#12);
#34= SQUARE_U_PROFILE($,#38,$,$,$,$);
#35= PLANE('SLOT1 DEPTH',#36);
#36= AXIS2_PLACEMENT_3D('SLOT1 DEPTH',#37,#11,#12);
#37= CARTESIAN_POINT('SLOT1 DEPTH',(0.000,0.000,-5.000));
#38= TOLERANCED_LENGTH_MEASURE(10.000,#90);
#39= RADIUSED_SLOT_END_TYPE();
#40= SLOT('SLOT2',#3,(#51,#52),#41,#45,#43,#44,({open_end},{open_end}));
#41= AXIS2_PLACEMENT_3D('SLOT2',#42,#11,#12);
#42= CARTESIAN_POINT('SLOT2',(90.000,0.000,0.000));
#43= LINEAR_PATH(#4,80.000,#16);
#44= SQUARE_U_PROFILE($,#48,$,90.000,$,90.000);
#45= PLANE('SLOT2 DEPTH',#46);
#46= AXIS2_PLACEMENT_3D('SLOT2 DEPTH',#47,#11,#12);
#47= CARTESIAN_POINT('SLOT2 DEPTH',(0.000,0.000,-6.000));
#48= TOLERANCED_LENGTH_MEASURE(16.000,#90);
#49= OPEN_SLOT_END_TYPE();
#59= FLAT_SLOT_END_TYPE($,$);
#58= WOODRUFF_SLOT_END_TYPE(#38);
#50= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'SLOT SLOT1',5.000,$,#22,#24,#25,$,#26,$,$,2.500,$,$,$);
#51= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH SLOT2',5.000,$,#22,#24,#25,$,#26,$,#27,3.000,$,0.500,0.200);
#52= BOTTOM_AND_SIDE_FINISH_MILLING($,$,'FINISH SLOT2',5.000,$,#22,#24,#25,$,#26,$,#28,3.000,$,$,$);
#60= MACHINING_WORKINGSTEP('WS SLOT1',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS ROUGH SLOT2',#6,#40,#51,$);
#62= MACHINING_WORKINGSTEP('WS FINISH SLOT2',#6,#40,#52,$);
#90= PLUS_MINUS_VALUE(0.010,0.010,3);
ENDSEC;
END-ISO-10303-21;
"""


def slot_from_text(text, name):
    """(start xy, direction xy, length, width, depth) of a SLOT, read with regular expressions."""
    slot = re.search(rf"^#\d+= SLOT\('{name}',#\d+,\([^)]*\),#(\d+),#(\d+),#(\d+),#(\d+),", text, re.MULTILINE)
    def line(ident):
        return re.search(rf"^#{ident}= (\w+)\((.*)\);$", text, re.MULTILINE).groups()
    def numbers(ident):
        return np.array([float(v) for v in re.search(r"\(([-\d.,]+)\)", line(ident)[1]).group(1).split(",")])
    location = numbers(line(slot.group(1))[1].split(",")[1].strip("#"))
    depth = -numbers(line(line(slot.group(2))[1].split(",")[1].strip("#"))[1].split(",")[1].strip("#"))[2]
    path = line(slot.group(3))[1].split(",")
    direction, length = numbers(path[2].strip("#")), float(path[1])
    width = float(re.search(r"([\d.]+)", line(line(slot.group(4))[1].split(",")[1].strip("#"))[1]).group(1))
    return location[:2], direction[:2], length, width, depth


@pytest.fixture(scope="module")
def slots():
    text = slot_file()
    loaded = load_workplan(text)
    return text, loaded, to_program(loaded)


def test_tool_wide_slot_runs_its_centre_line(slots):
    text, loaded, program = slots
    start, direction, length, width, depth = slot_from_text(text, "SLOT1")
    op = program.operations[0]
    cuts = op.xyz[op.kind == FEED]
    assert np.allclose(cuts[:, 1], start[1])                               # on the centre line
    assert cuts[:, 0].min() == pytest.approx(start[0]) and cuts[:, 0].max() == pytest.approx(start[0] + length)
    assert cuts[:, 2].min() == pytest.approx(-depth)
    assert sorted({round(z, 6) for z in cuts[:, 2]} & {-2.5, -5.0}) == [-5.0, -2.5]   # 2.5 mm layers


def test_open_slot_is_cut_past_both_ends_and_to_its_width(slots):
    text, loaded, program = slots
    start, direction, length, width, depth = slot_from_text(text, "SLOT2")
    rough, finish = program.operations[1:]
    r = 5.0
    walls = finish.xyz[(finish.kind == FEED) & (finish.xyz[:, 2] > -depth + 0.2 + 1e-9)]
    assert np.abs(walls[:, 0] - start[0]).max() == pytest.approx(width / 2 - r, abs=0.01)
    cuts = rough.xyz[rough.kind == FEED]
    assert np.abs(cuts[:, 0] - start[0]).max() <= width / 2 - r - 0.5 + 0.01
    # open ends: the tool passes the plate's edges completely
    assert cuts[:, 1].min() <= start[1] - r and cuts[:, 1].max() >= start[1] + length + r
    assert finish.xyz[finish.kind == FEED][:, 2].min() == pytest.approx(-depth)


def test_simulated_slots_have_their_volume_and_no_findings(slots):
    text, loaded, program = slots
    _, _, length1, width1, depth1 = slot_from_text(text, "SLOT1")
    _, _, length2, width2, depth2 = slot_from_text(text, "SLOT2")
    result = simulate(program, STOCK, cell=0.2)
    assert result.findings == []
    slot1 = (length1 * width1 + math.pi * (width1 / 2) ** 2) * depth1       # radiused ends: a stadium
    slot2 = length2 * width2 * depth2                                         # open across the plate
    # the slots do not meet (SLOT1 ends at X 65, SLOT2 starts at X 82)
    assert result.removed_volume_mm3 == pytest.approx(slot1 + slot2, rel=0.003)


def test_every_order_is_safe(slots):
    _, loaded, _ = slots
    ids = [step.id for step in loaded.workingsteps]
    for order in itertools.permutations(ids):
        result = simulate(to_program(loaded, order=list(order)), STOCK, cell=0.4)
        assert [f for f in result.findings if f.kind == "rapid_in_material"] == [], order


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_accepts_the_slots(slots):
    _, _, program = slots
    kinds, points, _ = rs274.motion_endpoints(rs274.run(post.milling_post("linuxcnc").to_text(program)))
    feeds = points[np.array(kinds) == "feed"]
    assert feeds[:, 2].min() == pytest.approx(-6.0, abs=1e-3)


def test_flat_and_unsupported_ends():
    flat = to_program(load_workplan(slot_file(second_end="#59")))
    op = flat.operations[0]
    cuts = op.xyz[op.kind == FEED]
    start, _, length, _, _ = slot_from_text(slot_file(), "SLOT1")
    assert cuts[:, 0].max() == pytest.approx(start[0] + length - 5.0)     # the edge stops on the flat end
    assert any("flat end of slot #30" in note for note in flat.notes)
    woodruff = load_workplan(slot_file(first_end="#58"))
    assert [step.id for step in woodruff.workingsteps] == [61, 62]
    assert any("WOODRUFF_SLOT_END_TYPE" in warning and "#60" in warning for warning in woodruff.warnings)
