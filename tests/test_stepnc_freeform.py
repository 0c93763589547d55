"""FREEFORM_OPERATION with explicit toolpaths and RAPID_MOVEMENT, in the conventions of NIST's ex1E.

Our own Part 21 file, written the way NIST's ISO 14649 toolkit writes explicit toolpaths (ex1E): a
TOOLPATH_LIST of CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,speed,technology,$,$,curve,$,$)
whose curves are in the feature's coordinates, POLYLINEs, TRIMMED_CURVEs on a LINE, a CIRCLE and a
HELIX(name, position, radius, pitch), and RAPID_MOVEMENT(id, secplane, toolpath list, $) in the
workpiece's coordinates.  A 120 x 80 x 30 plate: a 10 mm hole plunged 10 deep at X20 Y20 with a 10 mm
end mill, then a 40 x 24 pocket (corner radius 5) 4 deep at X70 Y40 entered by a 3-turn helix and
cleared by a ring, a centre line and an arc.  The expected numbers are read from the text.
"""
import math
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID
from kezuri.toolpath.simulate import BoxStock, blocking, simulate
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program

STOCK = BoxStock(0, 0, -30, 120, 80, 0)


def freeform_file(pocket_list="#401", hole_speed="$", pocket_operation="#51", before="") -> str:
    return f"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: EXPLICIT TOOLPATHS'),'2;1');
FILE_NAME('freeform.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('FREEFORM',#2,(#3),$,$,$);
#2= WORKPLAN('MAIN WORKPLAN',({before}#60,#65,#61),$,#5,$);
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
#14= CARTESIAN_POINT('SECURITY PLANE',(0.000,0.000,20.000));
#15= CARTESIAN_POINT('BLOCK CORNER',(0.000,0.000,-30.000));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(10.000,$,$,25.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(25.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.020,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#26= MILLING_TECHNOLOGY(0.010,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#27= MILLING_TECHNOLOGY(0.005,.TCP.,$,-80.000,$,.F.,.F.,.F.,$);
#30= ROUND_HOLE('HOLE1',#3,(#50),#31,#33,#36,$,#37);
#31= AXIS2_PLACEMENT_3D('HOLE1',#32,#11,#12);
#32= CARTESIAN_POINT('HOLE1: LOCATION ',(20.000,20.000,0.000));
#33= PLANE('HOLE1 DEPTH',#34);
#34= AXIS2_PLACEMENT_3D('HOLE1 DEPTH',#35,#11,#12);
#35= CARTESIAN_POINT('HOLE1: DEPTH ',(0.000,0.000,-10.000));
#36= TOLERANCED_LENGTH_MEASURE(10.000,#90);
#37= FLAT_HOLE_BOTTOM();
#40= CLOSED_POCKET('POCKET1',#3,(#51),#41,#43,(),$,#46,$,#47,#48);
#41= AXIS2_PLACEMENT_3D('POCKET1',#42,#11,#12);
#42= CARTESIAN_POINT('POCKET1: LOCATION ',(70.000,40.000,0.000));
#43= PLANE('POCKET1 DEPTH',#44);
#44= AXIS2_PLACEMENT_3D('POCKET1 DEPTH',#45,#11,#12);
#45= CARTESIAN_POINT('POCKET1: DEPTH ',(0.000,0.000,-4.000));
#46= PLANAR_POCKET_BOTTOM_CONDITION();
#47= TOLERANCED_LENGTH_MEASURE(5.000,#90);
#48= RECTANGULAR_CLOSED_PROFILE($,#49,#39);
#49= TOLERANCED_LENGTH_MEASURE(24.000,#90);
#39= TOLERANCED_LENGTH_MEASURE(40.000,#90);
#50= FREEFORM_OPERATION(#301,$,'PLUNGE HOLE1',5.000,$,#22,#27,#25,$,$,$,$);
#51= FREEFORM_OPERATION({pocket_list},$,'MILL POCKET1',5.000,$,#22,#24,#25,$,$,$,$);
#52= FREEFORM_OPERATION($,$,'POCKET1 BY STRATEGY',5.000,$,#22,#24,#25,$,$,$,#53);
#53= PLANE_CL_STRATEGY(.FORWARD.,.CLIMB.,$,$,#11,$);
#60= MACHINING_WORKINGSTEP('WS PLUNGE HOLE1',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS MILL POCKET1',#6,#40,{pocket_operation},$);
#65= RAPID_MOVEMENT('rapid up after the hole',#6,#701,$);
#66= RAPID_MOVEMENT('rapid before anything',#6,#701,$);
#90= PLUS_MINUS_VALUE(0.010,0.010,3);
/* the hole: down the axis at the slow feed, back up at rapid (hole coordinates) */
#301= TOOLPATH_LIST((#302,#312));
#302= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#303,$,$);
#303= TRIMMED_CURVE('plunge',#306,(#304),(#305),.T.,.CARTESIAN.);
#304= CARTESIAN_POINT('above hole',(0.000,0.000,5.000));
#305= CARTESIAN_POINT('hole bottom',(0.000,0.000,-10.000));
#306= LINE('hole axis',#307,#308);
#307= CARTESIAN_POINT('hole axis origin',(0.000,0.000,0.000));
#308= VECTOR('hole axis vector',#309,1.000);
#309= DIRECTION('down',(0.000,0.000,-1.000));
#312= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,{hole_speed},$,$,$,#313,$,$);
#313= POLYLINE('back up',(#305,#304));
/* the pocket (pocket coordinates): helix entry at its own feed, ring and centre line, an arc, rapid out */
#401= TOOLPATH_LIST((#402,#412,#422,#432));
#402= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,#26,$,$,#403,$,$);
#403= TRIMMED_CURVE('helical entry',#406,(#404),(#405),.F.,.CARTESIAN.);
#404= CARTESIAN_POINT('helix start',(4.000,0.000,2.000));
#405= CARTESIAN_POINT('helix end',(4.000,0.000,-4.000));
#406= HELIX('entry helix',#407,4.000,2.000);
#407= AXIS2_PLACEMENT_3D('entry helix axis',#408,#11,#12);
#408= CARTESIAN_POINT('entry helix centre',(0.000,0.000,-4.000));
#412= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#413,$,$);
#413= POLYLINE('ring and centre line',(#405,#414,#415,#416,#417,#418,#419,#420));
#414= CARTESIAN_POINT('',(15.000,0.000,-4.000));
#415= CARTESIAN_POINT('',(15.000,7.000,-4.000));
#416= CARTESIAN_POINT('',(-15.000,7.000,-4.000));
#417= CARTESIAN_POINT('',(-15.000,-7.000,-4.000));
#418= CARTESIAN_POINT('',(15.000,-7.000,-4.000));
#419= CARTESIAN_POINT('',(15.000,0.000,-4.000));
#420= CARTESIAN_POINT('',(-15.000,0.000,-4.000));
#422= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#423,$,$);
#423= TRIMMED_CURVE('arc',#426,(#420),(#424),.T.,.CARTESIAN.);
#424= CARTESIAN_POINT('arc end',(-5.000,0.000,-4.000));
#426= CIRCLE('arc circle',#427,5.000);
#427= AXIS2_PLACEMENT_3D('arc centre',#428,#11,#12);
#428= CARTESIAN_POINT('arc centre',(-10.000,0.000,-4.000));
#432= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,.RAPID.,$,$,$,#433,$,$);
#433= POLYLINE('out',(#424,#434));
#434= CARTESIAN_POINT('',(-5.000,0.000,10.000));
#501= TOOLPATH_LIST((#502));
#502= CUTTER_CONTACT_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#413,$,$);
#701= TOOLPATH_LIST((#702));
#702= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#703,$,$);
#703= POLYLINE('rapid up',(#710,#711));
#710= CARTESIAN_POINT('',(20.000,20.000,5.000));
#711= CARTESIAN_POINT('',(20.000,20.000,20.000));
ENDSEC;
END-ISO-10303-21;
"""


def numbers(text, ident):
    line = re.search(rf"^#{ident}= .*$", text, re.MULTILINE).group(0)
    return np.array([float(v) for v in re.search(r"\(([-\d.,]+)\)\);$", line).group(1).split(",")])


@pytest.fixture(scope="module")
def freeform():
    text = freeform_file()
    loaded = load_workplan(text)
    return text, loaded, to_program(loaded)


def test_the_hole_is_plunged_where_the_feature_puts_its_path(freeform):
    text, loaded, program = freeform
    hole = numbers(text, 32)
    op = program.operations[0]
    cuts = op.xyz[op.kind == FEED]
    assert np.allclose(cuts[:, :2], hole[:2])                                  # hole coordinates -> X20 Y20
    assert cuts[:, 2].min() == pytest.approx(hole[2] + numbers(text, 305)[2])
    assert np.allclose(op.feed[op.kind == FEED], 0.005 * 60000)               # the operation's technology #27
    # back up at rapid, then the RAPID_MOVEMENT after the workingstep: up to Z20 (workpiece coordinates)
    rapids = op.xyz[op.kind == RAPID]
    assert any(np.allclose(p, hole[:2].tolist() + [hole[2] + 5.0]) for p in rapids)
    assert any(np.allclose(p, numbers(text, 711)) for p in rapids)


def test_the_helix_arcs_and_lines_are_the_files(freeform):
    text, loaded, program = freeform
    centre = numbers(text, 42)
    op = program.operations[1]
    arcs = np.flatnonzero(np.isin(op.kind, (ARC_CW, ARC_CCW)))
    helix = [i for i in arcs if op.feed[i] == pytest.approx(0.010 * 60000)]
    # 3 turns down (rise 6, pitch 2), clockwise (against the parameter), cut in half turns
    assert len(helix) == 6 and all(op.kind[i] == ARC_CW for i in helix)
    assert np.allclose(op.center[helix][:, :2], centre[:2])
    assert np.allclose(np.linalg.norm(op.xyz[helix][:, :2] - centre[:2], axis=1), 4.0)
    assert np.allclose(op.xyz[helix][:, 2], np.linspace(2.0, -4.0, 7)[1:])
    # the arc about (-10, 0): counter-clockwise (sense .T.) from (-15, 0) to (-5, 0), through Y -5
    last = [i for i in arcs if i not in helix]
    assert len(last) == 1 and op.kind[last[0]] == ARC_CCW
    assert np.allclose(op.center[last[0]][:2], centre[:2] + [-10.0, 0.0])
    cuts = op.xyz[op.kind == FEED]
    assert cuts[:, 0].min() == pytest.approx(centre[0] - 15) and cuts[:, 0].max() == pytest.approx(centre[0] + 15)
    assert cuts[:, 1].min() == pytest.approx(centre[1] - 7) and cuts[:, 1].max() == pytest.approx(centre[1] + 7)
    assert np.allclose(op.feed[op.kind == FEED], 0.020 * 60000)
    assert op.xyz[op.kind == RAPID][:, 2].max() >= 10.0 - 1e-9


def test_simulated_volume_is_the_hole_and_the_pocket(freeform):
    text, loaded, program = freeform
    result = simulate(program, STOCK, cell=0.2)
    assert blocking(result.findings) == []
    r = 5.0
    pocket = (40 * 24 - (4 - math.pi) * 5.0 ** 2) * 4.0          # rounded rectangle, corners = tool radius
    hole = math.pi * r ** 2 * 10.0
    assert result.removed_volume_mm3 == pytest.approx(pocket + hole, rel=0.01)


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_accepts_the_explicit_toolpaths(freeform):
    _, _, program = freeform
    text = post.milling_post("linuxcnc").to_text(program)
    assert re.search(r"^G2 ", text, re.MULTILINE) or " G2 " in text or "\nG2" in text
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
    feeds = points[np.array(kinds) != "traverse"]
    assert feeds[:, 2].min() == pytest.approx(-10.0, abs=1e-3)


def test_what_is_not_converted_is_named():
    contact = load_workplan(freeform_file(pocket_list="#501"))
    assert [s.id for s in contact.workingsteps] == [60]
    assert any("workingstep #61 'WS MILL POCKET1' skipped: CUTTER_CONTACT_TRAJECTORY #502 is not supported" in w
               for w in contact.warnings)
    strategy = load_workplan(freeform_file(pocket_operation="#52"))
    assert any("#61" in w and "FREEFORM_OPERATION #52 is not supported (no explicit toolpaths" in w
               for w in strategy.warnings)
    first = load_workplan(freeform_file(before="#66,"))
    assert any("rapid movement #66 'rapid before anything' skipped: no workingstep before it" in w
               for w in first.warnings)
    speed = load_workplan(freeform_file(hole_speed="#26"))
    assert any("workingstep #60" in w and "a speed profile" in w for w in speed.warnings)


def test_an_arc_whose_points_are_off_its_circle_is_refused_by_name():
    from kezuri.toolpath.operations.stepnc.errors import StepNcError
    text = freeform_file().replace("#426= CIRCLE('arc circle',#427,5.000);", "#426= CIRCLE('arc circle',#427,4.000);")
    with pytest.raises(StepNcError, match=r"#423 TRIMMED_CURVE: its points lie 5 and 5 mm from the axis of #426, "
                                          r"whose radius is 4 mm"):
        to_program(load_workplan(text))


# --------------------------------------------------------------------------- feeds where NIST's files state them

# A second toolpath list for the pocket that starts at the ring's first point, 4 mm below the top (as NIST's
# ex1E 'ROUGH POCKET1 B' starts on the material): the tool rapids to 2 mm above the material and is fed in.
FED_IN = "#1401= TOOLPATH_LIST((#412,#422,#432));"


def test_a_path_starting_in_the_material_is_fed_in_at_its_feed():
    from test_stepnc import add_instances
    program = to_program(load_workplan(add_instances(freeform_file(pocket_list="#1401"), FED_IN)))
    op = program.operations[1]
    first_feed = int(np.flatnonzero(op.kind == FEED)[0])
    assert op.xyz[first_feed - 1][2] == pytest.approx(2.0)            # the rapid stops 2 mm above the top (Z 0)
    assert op.xyz[first_feed][2] == pytest.approx(-4.0)               # fed down to the path's first point
    assert op.feed[first_feed] == pytest.approx(0.020 * 60000)        # at #412's feed: the operation's #24
    if rs274.available():
        calls = rs274.run(post.milling_post("linuxcnc").to_text(program))
        rates = [float(args[0]) for name, args in calls if name == "SET_FEED_RATE"]
        assert 1200.0 in rates


def test_no_feed_anywhere_names_what_is_missing_where():
    from test_stepnc import add_instances
    text = add_instances(freeform_file(pocket_list="#1401"), FED_IN,
                         "#1402= MILLING_TECHNOLOGY($,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);")
    text = text.replace("#24= MILLING_TECHNOLOGY(0.020,", "#24= MILLING_TECHNOLOGY($,")
    text = text.replace("#412= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,", "#412= CUTTER_LOCATION_TRAJECTORY("
                        ".T.,.TRAJECTORY_PATH.,$,#1402,")
    program = to_program(load_workplan(text))
    assert [op.name for op in program.operations] == ["WS PLUNGE HOLE1"]          # the pocket is left out, said why
    note = [n for n in program.notes if n.startswith("workingstep #61 'WS MILL POCKET1' skipped: ")]
    assert note == ["workingstep #61 'WS MILL POCKET1' skipped: #412 CUTTER_LOCATION_TRAJECTORY: its_technology #1402 "
                    "MILLING_TECHNOLOGY gives no feedrate (attribute 1) nor feedrate_per_tooth (attribute 5) with the "
                    "tool's number_of_teeth, and #51 FREEFORM_OPERATION's its_technology #24 MILLING_TECHNOLOGY gives no "
                    "feedrate (attribute 1) nor feedrate_per_tooth (attribute 5) with #20 ENDMILL's number_of_teeth: no "
                    "feed for its cutting moves"]
