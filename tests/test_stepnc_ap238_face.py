"""A planar face roughed then finished, in the AP238 integrated form: the gate passes it.

Our own file in the layout of ISO 10303-238 Annex J (tests/fixtures/iso14649/ex1_ap238.stp with more
instances): the workpiece gets its stock as a BLOCK_SHAPE_REPRESENTATION (100 x 120 x 35, the face's
extent, Z -30 to 5) through a MAKE_FROM_USAGE_OPTION, and PLANAR FACE1 gets a roughing workingstep
before its finishing one: a PLANE_MILLING_OPERATION 'roughing' with a 50 mm 'facemill' named 'T5 ...',
'bidirectional' along X (the finishing runs along Y), 2 mm layers, 'allowance bottom' 0.5 mm.  The
finishing (the 18 mm end mill, 2.5 mm layers) then starts at the rough floor, Z 0.5: its approach must
stop above what the roughing left (the in-process stock), never rapid into those 0.5 mm, whatever the
order of the workingsteps.  Checked by the simulation the export gate runs (0.1 mm cells) and on the
NC text by rs274 and the rules checker."""
import itertools
import math
import os

import numpy as np
import pytest

import controller_rules as rules
import rs274
from kezuri import post
from kezuri.toolpath import simulate
from kezuri.toolpath.ir.program import RAPID
from kezuri.toolpath.operations.stepnc.solids import fixture_clearance, stock_box
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program

AIM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "iso14649", "ex1_ap238.stp")


def length(ident, value, name):
    return (f"#{ident}=(LENGTH_MEASURE_WITH_UNIT()MEASURE_REPRESENTATION_ITEM()MEASURE_WITH_UNIT("
            f"LENGTH_MEASURE({value}),#900)REPRESENTATION_ITEM('{name}'));")


def prop(owner, ident, name, description, value_line):
    """An ACTION_PROPERTY of ``owner`` with a REPRESENTATION of one item (ids ident .. ident + 2)."""
    return [f"#{ident}=ACTION_PROPERTY('{name}','{description}',#{owner});",
            f"#{ident + 1}=ACTION_PROPERTY_REPRESENTATION('','{description}',#{ident},#{ident + 2});",
            f"#{ident + 2}=REPRESENTATION('',(#{ident + 3}),#901);", value_line.format(ident + 3)]


ROUGHING = [
    "/* WORKINGSTEP 'WS ROUGH PLANAR FACE1' (before the finishing: sequence 0.5) */",
    "#60000=MACHINING_WORKINGSTEP('WS ROUGH PLANAR FACE1','machining','','');",
    "#60001=MACHINING_OPERATION_RELATIONSHIP('','machining',#60000,#60100);",
    "#60002=MACHINING_FEATURE_RELATIONSHIP('','machining',#60000,#60003);",
    "#60003=MACHINING_FEATURE_PROCESS('','machining','','');",
    "#60004=PROPERTY_PROCESS('machining','machining',#60003,'');",
    "#60005=PROCESS_PROPERTY_ASSOCIATION('','machining',#60004,#16);",
    "#60006=ACTION_PROPERTY('security plane','machining',#60000);",
    "#60007=ACTION_PROPERTY_REPRESENTATION('','machining',#60006,#1008);",
    "#60008=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#2,#60000,0.5);",
    "/* PLANE_ROUGH_MILLING 'ROUGH PLANAR FACE1' */",
    "#60100=PLANE_MILLING_OPERATION('ROUGH PLANAR FACE1','roughing','','');",
    *prop(60100, 60110, "retract plane", "roughing", length("{}", "10.000", "")),
    *prop(60100, 60120, "axial cutting depth", "roughing", length("{}", "2.000", "")),
    *prop(60100, 60130, "allowance bottom", "roughing", length("{}", "0.500", "")),
    "#60140=MACHINING_TECHNOLOGY_RELATIONSHIP('','roughing',#60100,#40);",
    "#60141=MACHINING_FUNCTIONS_RELATIONSHIP('','roughing',#60100,#41000);",
    "#60142=MACHINING_STRATEGY_RELATIONSHIP('approach','roughing',#60100,#60);",
    "#60143=MACHINING_STRATEGY_RELATIONSHIP('retract','roughing',#60100,#61);",
    "#60144=MACHINING_STRATEGY_RELATIONSHIP('machining','roughing',#60100,#60200);",
    "/* MILLING_TYPE_STRATEGY 'bidirectional' along X, overlap 0.2 */",
    "#60200=MILLING_TYPE_STRATEGY('','bidirectional','','');",
    *prop(60200, 60210, "feed direction", "bidirectional", "#{}=DIRECTION('ALONG X',(1.000,0.000,0.000));"),
    *prop(60200, 60220, "stepover direction", "bidirectional", "#{}=DESCRIPTIVE_REPRESENTATION_ITEM('','left');"),
    *prop(60200, 60230, "overlap ratio", "bidirectional",
          "#{}=(MEASURE_REPRESENTATION_ITEM()MEASURE_WITH_UNIT(RATIO_MEASURE(0.2),#916)RATIO_MEASURE_WITH_UNIT()"
          "REPRESENTATION_ITEM(''));"),
    "/* FACEMILL 'T5 50 MM FACE MILL' */",
    "#60300=MACHINING_TOOL('T5 50 mm face mill','facemill',(#60100),#3900);",
    "#60301=RESOURCE_PROPERTY('tool body','',#60300);",
    "#60302=RESOURCE_PROPERTY_REPRESENTATION('','',#60301,#60303);",
    "#60303=MACHINING_TOOL_BODY_REPRESENTATION('facemill',(#60304,#60305,#60306,#60307),#901);",
    length(60304, "50.000", "effective cutting diameter"), length(60305, "8.000", "maximum depth of cut"),
    length(60306, "0.000", "edge radius"),
    "#60307=MEASURE_REPRESENTATION_ITEM('number of effective teeth',COUNT_MEASURE(6.),#917);",
    "/* the stock: a BLOCK 100 x 120 x 35 from (0, 0, -30) */",
    "#60400=MAKE_FROM_USAGE_OPTION('','','',#4,#60401,0,'',$);",
    "#60401=PRODUCT_DEFINITION($,$,$,#920);",
    "#60402=PRODUCT_DEFINITION_SHAPE('','',#60401);",
    "#60403=SHAPE_DEFINITION_REPRESENTATION(#60402,#60404);",
    "#60404=BLOCK_SHAPE_REPRESENTATION('STOCK',(#60405,#60408,#60409,#60410),#902);",
    "#60405=AXIS2_PLACEMENT_3D('orientation',#60406,#96,#97);",
    "#60406=CARTESIAN_POINT('STOCK CORNER',(0.000,0.000,-30.000));",
    length(60408, "100.000", "length"), length(60409, "120.000", "width"), length(60410, "35.000", "height"),
]


def face_file() -> str:
    with open(AIM, encoding="latin-1") as stream:
        text = stream.read()
    head, _, tail = text.rpartition("ENDSEC;")
    return head + "\n".join(ROUGHING) + "\nENDSEC;" + tail


@pytest.fixture(scope="module")
def loaded():
    return load_workplan(face_file())


def test_the_face_is_roughed_then_finished(loaded):
    assert [s.id for s in loaded.workingsteps] == [60000, 10, 11, 12, 13, 14]
    rough = loaded.workingsteps[0].its_operation
    assert rough.type_name == "PLANE_ROUGH_MILLING" and rough.allowance_bottom == pytest.approx(0.5)
    assert loaded.project.its_workpieces[0].its_bounding_geometry.box() == ((0, 0, -30), (100, 120, 5))
    program = to_program(loaded)
    ops = {op.name: op for op in program.operations}
    face_rough, face_finish = ops["WS ROUGH PLANAR FACE1"], ops["WS FINISH PLANAR FACE1"]
    assert face_rough.tool.number == 5 and face_rough.tool.diameter == 50.0      # the file's 'T5 ...'
    # roughing layers (level cutting moves) at 3.5, 2 and 0.5 (Z 5 to the 0.5 allowance in 2 mm steps: 3 layers
    # of 1.5), finishing one layer at Z 0
    def layers(op):
        level = (op.kind != RAPID) & (np.abs(op.start_points()[:, 2] - op.xyz[:, 2]) < 1e-9)
        return sorted(set(np.round(op.xyz[level][:, 2], 6)))
    assert layers(face_rough) == [0.5, 2.0, 3.5]
    assert layers(face_finish) == [0.0]
    # the finishing rapids stop APPROACH_GAP (2 mm) above the rough floor (Z 0.5) or higher: never into it
    rapid_low = face_finish.xyz[face_finish.kind == RAPID][:, 2].min()
    assert rapid_low >= 0.5 + 2.0 - 1e-9


@pytest.mark.parametrize("order", [None, [10, 60000, 11, 12, 13, 14], [13, 14, 10, 60000, 11, 12]])
def test_the_gate_simulation_finds_nothing_in_any_order(loaded, order):
    program = to_program(loaded, order=order)
    result = simulate.simulate(program, stock_box(loaded, program), cell=0.1,
                               fixture_clearance=fixture_clearance(loaded))
    assert simulate.blocking(result.findings) == []


def test_the_nc_passes_rs274_and_the_rules(loaded):
    program = to_program(loaded)
    for name, control in (("linuxcnc", "linuxcnc"), ("fanuc", "fanuc-mill"), ("grbl", "grbl")):
        assert rules.check(post.milling_post(name).to_text(program), control) == [], name
    if rs274.available():
        text = post.milling_post("linuxcnc").to_text(program)
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(1, 2, 3, 5)))
        assert len(points) > 50


def test_the_export_gate_writes_it(tmp_path):
    pytest.importorskip("bpy")
    from kezuri.operators import gate, stepnc as shell
    from test_gate import planned_workplan
    path = tmp_path / "face_ap238.stp"
    path.write_text(face_file(), encoding="latin-1")
    _, report = gate.check(shell.simulation(planned_workplan(str(path))))
    assert report["findings"] == [] and not report["overridden"]
    assert math.isfinite(report["seconds"])


def test_every_order_of_the_face_and_pocket_steps_is_clean(loaded):
    """Links know the material whatever the order: every order of the face and pocket steps."""
    for order in itertools.islice(itertools.permutations([60000, 10, 13, 14]), 0, 24, 5):
        program = to_program(loaded, order=list(order) + [11, 12])
        result = simulate.simulate(program, stock_box(loaded, program), cell=0.25,
                                   fixture_clearance=fixture_clearance(loaded))
        assert [f.message for f in simulate.blocking(result.findings)] == [], order
