"""AP238 slots on curved paths and a stock BLOCK, read like their ISO 14649 rendition.

Our own AP238 rendition (laid out as ISO 10303-238 Annex J lays out its examples, with the slot
attributes the AIM's rules name: PATH_FEATURE_COMPONENT 'partial circular' with 'radius' and 'sweep
angle', 'complex' with a PATH_SHAPE_REPRESENTATION 'sweep path', SQUARE_U_PROFILE 'width', SLOT_ENDs
tied as 'course of travel start' / 'end') of two workingsteps of test_stepnc_slot_paths.py's ISO 14649
file: the 10 mm slot on a quarter circle and the roughing of the L-shaped 16 mm slot, on the
120 x 80 x 30 plate given as a BLOCK_SHAPE_REPRESENTATION.  Both renditions must give the same NC.
"""
import pytest

from kezuri import post
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program
from test_stepnc_slot_paths import slot_file


def length(ident, value, name="", unit="#900"):
    return (f"#{ident}=(LENGTH_MEASURE_WITH_UNIT()MEASURE_REPRESENTATION_ITEM()MEASURE_WITH_UNIT("
            f"LENGTH_MEASURE({value}),{unit})REPRESENTATION_ITEM('{name}'));")


def prop(owner, ident, name, item, rep_type="REPRESENTATION", link_name=""):
    return (f"#{ident}=ACTION_PROPERTY('{name}','',#{owner});\n"
            f"#{ident + 1}=ACTION_PROPERTY_REPRESENTATION('{link_name}','',#{ident},#{ident + 2});\n"
            f"#{ident + 2}={rep_type}('',(#{item}),#901);")


AIM = "\n".join([
    "ISO-10303-21;", "HEADER;", "FILE_DESCRIPTION(('KEZURI TEST: AP238 CURVED SLOTS'),'2;1');",
    "FILE_NAME('slots_ap238.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');",
    "FILE_SCHEMA(('AP238_STEP_NC_MIM'));", "ENDSEC;", "DATA;",
    "#900=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));",
    "#901=REPRESENTATION_CONTEXT('','units not necessary');",
    "#902=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#900,#903))"
    "REPRESENTATION_CONTEXT('',''));",
    "#903=(CONVERSION_BASED_UNIT('degree',#904)NAMED_UNIT(#905)PLANE_ANGLE_UNIT());",
    "#904=PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.01745329252),#906);",
    "#905=DIMENSIONAL_EXPONENTS(0.,0.,0.,0.,0.,0.,0.);",
    "#906=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));",
    "#907=(NAMED_UNIT(*)SI_UNIT($,.SECOND.)TIME_UNIT());",
    "#908=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.));",
    "#909=DERIVED_UNIT((#910,#911));", "#910=DERIVED_UNIT_ELEMENT(#908,1.);", "#911=DERIVED_UNIT_ELEMENT(#907,-1.);",
    "#913=DERIVED_UNIT((#914));", "#914=DERIVED_UNIT_ELEMENT(#907,-1.);",
    "#916=RATIO_UNIT(#905);", "#917=CONTEXT_DEPENDENT_UNIT(#905,'count');",
    "#918=APPLICATION_CONTEXT('Application protocol for the exchange of CNC data');",
    "#919=PRODUCT_CONTEXT('CNC Machining',#918,'manufacturing');",
    "#920=PRODUCT_DEFINITION_CONTEXT('CNC Machining',#918,'manufacturing');",
    "#922=FEATURE_COMPONENT_DEFINITION('feature component','shared by all');",
    "#923=PRODUCT_DEFINITION_SHAPE('feature component',$,#922);",
    "#11=DIRECTION('Z AXIS',(0.,0.,1.));", "#12=DIRECTION('X AXIS',(1.,0.,0.));",
    "#10=CARTESIAN_POINT('ORIGIN',(0.,0.,0.));",
    # project, workplan, setup
    "#1=MACHINING_PROJECT('CURVED SLOTS','',$,(#919));", "#100=PRODUCT_DEFINITION_FORMATION('','',#1);",
    "#101=PRODUCT_DEFINITION('','',#100,#920);", "#102=PRODUCT_DEFINITION_PROCESS('machining','',#2,'');",
    "#103=PROCESS_PRODUCT_ASSOCIATION('','',#101,#102);",
    "#104=MACHINING_PROJECT_WORKPIECE_RELATIONSHIP('','workpiece','',#101,#3);",
    "#2=MACHINING_WORKPLAN('MAIN WORKPLAN','','','');",
    "#105=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#2,#62,2.);",
    "#106=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#2,#60,1.);",
    "#107=PRODUCT_DEFINITION_PROCESS('setup','',#2,'');", "#108=PROCESS_PRODUCT_ASSOCIATION('','',#110,#107);",
    "#110=PRODUCT_DEFINITION('','',#111,#920);", "#111=PRODUCT_DEFINITION_FORMATION('','',#112);",
    "#112=MACHINING_SETUP('SETUP1','',$,(#919));", "#113=PROPERTY_DEFINITION('security plane','',#110);",
    "#114=PROPERTY_DEFINITION_REPRESENTATION(#113,#115);", "#115=REPRESENTATION('',(#6),#901);",
    "#6=PLANE('SECURITY PLANE',#9);", "#9=AXIS2_PLACEMENT_3D('SECURITY PLANE',#14,#11,#12);",
    "#14=CARTESIAN_POINT('SECURITY PLANE',(0.,0.,30.));",
    # workpiece and its stock block
    "#3=PRODUCT_DEFINITION('PLATE','',#120,#920);", "#120=PRODUCT_DEFINITION_FORMATION('1.0','Workpiece',#121);",
    "#121=PRODUCT('WP','PLATE','',(#919));", "#4=PRODUCT_DEFINITION_SHAPE('','',#3);",
    "#122=MAKE_FROM_USAGE_OPTION('','','',#3,#123,0,'',$);", "#123=PRODUCT_DEFINITION($,$,$,#920);",
    "#124=PRODUCT_DEFINITION_SHAPE('','',#123);", "#125=SHAPE_DEFINITION_REPRESENTATION(#124,#7);",
    "#7=BLOCK_SHAPE_REPRESENTATION('PLATE BLOCK',(#13,#126,#127,#128),#902);",
    "#13=AXIS2_PLACEMENT_3D('orientation',#15,#11,#12);", "#15=CARTESIAN_POINT('BLOCK CORNER',(0.,0.,-30.));",
    length(126, "120.", "length"), length(127, "80.", "width"), length(128, "30.", "height"),
    # tool, technology, functions, strategy
    "#22=MACHINING_TOOL('ENDMILL 10MM','endmill',(#50,#52),#130);",
    "#130=ACTION_RESOURCE_TYPE('milling cutting tool');", "#131=RESOURCE_PROPERTY('tool body','',#22);",
    "#132=RESOURCE_PROPERTY_REPRESENTATION('','',#131,#20);",
    "#20=MACHINING_TOOL_BODY_REPRESENTATION('endmill',(#133,#134,#135,#136),#901);",
    length(133, "10.", "effective cutting diameter"), length(134, "25.", "maximum depth of cut"),
    length(135, "0.", "edge radius"), "#136=MEASURE_REPRESENTATION_ITEM('number of effective teeth',"
    "COUNT_MEASURE(4.),#917);",
    "#24=MACHINING_TECHNOLOGY('','milling','','');",
    prop(24, 140, "feedrate", 143, "MACHINING_FEED_SPEED_REPRESENTATION", "feed speed"),
    "#143=MEASURE_REPRESENTATION_ITEM('feed speed',NUMERIC_MEASURE(0.015),#909);",
    prop(24, 144, "spindle", 147, "MACHINING_SPINDLE_SPEED_REPRESENTATION", "rotational speed"),
    "#147=MEASURE_REPRESENTATION_ITEM('rotational speed',NUMERIC_MEASURE(-100.),#913);",
    prop(24, 148, "feedrate reference", 151),
    "#151=DESCRIPTIVE_REPRESENTATION_ITEM('','tool center point');",
    "#25=MACHINING_FUNCTIONS('','milling','','');", prop(25, 152, "coolant", 155),
    "#155=DESCRIPTIVE_REPRESENTATION_ITEM('constant','coolant on');",
    "#27=MILLING_TYPE_STRATEGY('','bidirectional','','');",
    prop(27, 156, "overlap ratio", 159),
    "#159=(MEASURE_REPRESENTATION_ITEM()MEASURE_WITH_UNIT(RATIO_MEASURE(0.4),#916)RATIO_MEASURE_WITH_UNIT()"
    "REPRESENTATION_ITEM(''));",
    prop(27, 160, "multiple passes", 163), "#163=DESCRIPTIVE_REPRESENTATION_ITEM('','multiple passes allowed');",
    prop(27, 164, "stepover direction", 167), "#167=DESCRIPTIVE_REPRESENTATION_ITEM('','left');",
    # operations
    "#50=BOTTOM_AND_SIDE_MILLING_OPERATION('MILL ARC SLOT','roughing','','');",
    prop(50, 170, "retract plane", 173), length(173, "5."), prop(50, 174, "axial cutting depth", 177),
    length(177, "2."), "#178=MACHINING_TECHNOLOGY_RELATIONSHIP('','roughing',#50,#24);",
    "#179=MACHINING_FUNCTIONS_RELATIONSHIP('','roughing',#50,#25);",
    "#52=BOTTOM_AND_SIDE_MILLING_OPERATION('ROUGH L SLOT','roughing','','');",
    prop(52, 180, "retract plane", 173), prop(52, 183, "axial cutting depth", 186), length(186, "2.5"),
    prop(52, 187, "allowance side", 190), length(190, "0.5"), prop(52, 191, "allowance bottom", 194),
    length(194, "0.2"), "#195=MACHINING_TECHNOLOGY_RELATIONSHIP('','roughing',#52,#24);",
    "#196=MACHINING_FUNCTIONS_RELATIONSHIP('','roughing',#52,#25);",
    "#197=MACHINING_STRATEGY_RELATIONSHIP('machining','roughing',#52,#27);",
    # ARC SLOT: a quarter circle of R20 about its placement, 10 wide, 4 deep, radiused ends
    "#30=(CHARACTERIZED_OBJECT('','')FEATURE_DEFINITION()INSTANCED_FEATURE()SHAPE_ASPECT('ARC SLOT','',#4,.T.)"
    "SLOT());",
    "#300=PRODUCT_DEFINITION_SHAPE('','',#30);", "#301=SHAPE_DEFINITION_REPRESENTATION(#300,#302);",
    "#302=SHAPE_REPRESENTATION_WITH_PARAMETERS('',(#31),#902);",
    "#31=AXIS2_PLACEMENT_3D('orientation',#32,#11,#12);", "#32=CARTESIAN_POINT('ARC SLOT: CENTRE',(40.,40.,0.));",
    "#303=SHAPE_DEFINITION_REPRESENTATION(#300,#304);",
    "#304=SHAPE_REPRESENTATION('maximum feature limit',(#35),#902);",
    "#35=PLANE('ARC SLOT DEPTH',#36);", "#36=AXIS2_PLACEMENT_3D('ARC SLOT DEPTH',#37,#11,#12);",
    "#37=CARTESIAN_POINT('ARC SLOT DEPTH',(0.,0.,-4.));",
    "#305=SHAPE_ASPECT('','course of travel occurrence',#300,.F.);",
    "#306=SHAPE_DEFINING_RELATIONSHIP('course of travel','path feature component usage',#33,#305);",
    "#33=PATH_FEATURE_COMPONENT('','partial circular',#923,.F.);", "#307=PROPERTY_DEFINITION('','',#33);",
    "#308=SHAPE_DEFINITION_REPRESENTATION(#307,#309);",
    "#309=SHAPE_REPRESENTATION_WITH_PARAMETERS('',(#38,#310),#902);", length(38, "20.", "radius"),
    "#310=(MEASURE_REPRESENTATION_ITEM()MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(90.),#903)"
    "PLANE_ANGLE_MEASURE_WITH_UNIT()REPRESENTATION_ITEM('sweep angle'));",
    "#311=SHAPE_ASPECT('','swept shape occurrence',#300,.F.);",
    "#312=SHAPE_DEFINING_RELATIONSHIP('swept shape','profile usage',#34,#311);",
    "#34=SQUARE_U_PROFILE('','',#923,.F.);", "#313=PROPERTY_DEFINITION('','',#34);",
    "#314=SHAPE_DEFINITION_REPRESENTATION(#313,#315);",
    "#315=SHAPE_REPRESENTATION_WITH_PARAMETERS('',(#39),#902);", length(39, "10.", "width"),
    "#316=SHAPE_ASPECT('','end condition occurrence',#300,.F.);",
    "#317=FEATURE_COMPONENT_RELATIONSHIP('course of travel start','slot end usage',#318,#316);",
    "#318=SLOT_END('','radiused',#923,.F.);",
    "#319=SHAPE_ASPECT('','end condition occurrence',#300,.F.);",
    "#320=FEATURE_COMPONENT_RELATIONSHIP('course of travel end','slot end usage',#321,#319);",
    "#321=SLOT_END('','radiused',#923,.F.);",
    # L SLOT: a polyline from the plate's edge, 16 wide, 5 deep, open at the edge, radiused at the end
    "#70=(CHARACTERIZED_OBJECT('','')FEATURE_DEFINITION()INSTANCED_FEATURE()SHAPE_ASPECT('L SLOT','',#4,.T.)"
    "SLOT());",
    "#700=PRODUCT_DEFINITION_SHAPE('','',#70);", "#701=SHAPE_DEFINITION_REPRESENTATION(#700,#702);",
    "#702=SHAPE_REPRESENTATION_WITH_PARAMETERS('',(#71),#902);",
    "#71=AXIS2_PLACEMENT_3D('orientation',#72,#11,#12);", "#72=CARTESIAN_POINT('L SLOT: START',(80.,0.,0.));",
    "#703=SHAPE_DEFINITION_REPRESENTATION(#700,#704);",
    "#704=SHAPE_REPRESENTATION('maximum feature limit',(#75),#902);",
    "#75=PLANE('L SLOT DEPTH',#76);", "#76=AXIS2_PLACEMENT_3D('L SLOT DEPTH',#77,#11,#12);",
    "#77=CARTESIAN_POINT('L SLOT DEPTH',(0.,0.,-5.));",
    "#705=SHAPE_ASPECT('','course of travel occurrence',#700,.F.);",
    "#706=SHAPE_DEFINING_RELATIONSHIP('course of travel','path feature component usage',#73,#705);",
    "#73=PATH_FEATURE_COMPONENT('','complex',#923,.F.);", "#707=PROPERTY_DEFINITION('','',#73);",
    "#708=PROPERTY_DEFINITION_REPRESENTATION(#707,#709);", "#709=PATH_SHAPE_REPRESENTATION('sweep path',(#83),#902);",
    "#83=POLYLINE('L SLOT CENTRE LINE',(#84,#85,#86));", "#84=CARTESIAN_POINT('L1',(0.,0.,0.));",
    "#85=CARTESIAN_POINT('L2',(0.,20.,0.));", "#86=CARTESIAN_POINT('L3',(25.,20.,0.));",
    "#711=SHAPE_ASPECT('','swept shape occurrence',#700,.F.);",
    "#712=SHAPE_DEFINING_RELATIONSHIP('swept shape','profile usage',#74,#711);",
    "#74=SQUARE_U_PROFILE('','',#923,.F.);", "#713=PROPERTY_DEFINITION('','',#74);",
    "#714=SHAPE_DEFINITION_REPRESENTATION(#713,#715);",
    "#715=SHAPE_REPRESENTATION_WITH_PARAMETERS('',(#78),#902);", length(78, "16.", "width"),
    # the end first in the file: the relationship names say which is which
    "#719=SHAPE_ASPECT('','end condition occurrence',#700,.F.);",
    "#720=FEATURE_COMPONENT_RELATIONSHIP('course of travel end','slot end usage',#721,#719);",
    "#721=SLOT_END('','radiused',#923,.F.);",
    "#716=SHAPE_ASPECT('','end condition occurrence',#700,.F.);",
    "#717=FEATURE_COMPONENT_RELATIONSHIP('course of travel start','slot end usage',#722,#716);",
    "#722=SLOT_END('','open',#923,.F.);",
    # workingsteps
    "#60=MACHINING_WORKINGSTEP('WS ARC SLOT','machining','','');",
    "#600=MACHINING_OPERATION_RELATIONSHIP('','machining',#60,#50);",
    "#601=MACHINING_FEATURE_RELATIONSHIP('','machining',#60,#602);",
    "#602=MACHINING_FEATURE_PROCESS('','machining','','');", "#603=PROPERTY_PROCESS('machining','machining',#602,'');",
    "#604=PROCESS_PROPERTY_ASSOCIATION('','machining',#603,#30);", prop(60, 605, "security plane", 6),
    "#62=MACHINING_WORKINGSTEP('WS ROUGH L SLOT','machining','','');",
    "#620=MACHINING_OPERATION_RELATIONSHIP('','machining',#62,#52);",
    "#621=MACHINING_FEATURE_RELATIONSHIP('','machining',#62,#622);",
    "#622=MACHINING_FEATURE_PROCESS('','machining','','');", "#623=PROPERTY_PROCESS('machining','machining',#622,'');",
    "#624=PROCESS_PROPERTY_ASSOCIATION('','machining',#623,#70);", prop(62, 625, "security plane", 6),
    "ENDSEC;", "END-ISO-10303-21;", ""])


def test_the_ap238_slots_give_the_same_nc():
    arm = load_workplan(slot_file().replace("(#60,#61,#62,#63)", "(#60,#62)"))
    aim = load_workplan(AIM)
    assert aim.warnings == arm.warnings == ()
    assert aim.workingsteps[1].its_feature.ends == ("OPEN_SLOT_END_TYPE", "RADIUSED_SLOT_END_TYPE")
    assert aim.workingsteps[0].its_feature.course_of_travel.sweep_angle == pytest.approx(90.0)
    assert aim.project.its_workpieces[0].its_bounding_geometry.box() == \
        arm.project.its_workpieces[0].its_bounding_geometry.box()
    text = post.milling_post("linuxcnc").to_text
    assert text(to_program(aim)) == text(to_program(arm))
