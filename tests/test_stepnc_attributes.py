"""ISO 14649 attributes are read with their meaning, not at face value (issue 27): an allowance is
0 or more, a cutting depth, radial depth and hole diameter above 0, an overlap a ratio in (0, 1], a
tool no wider than the feature it makes, a depth within the workpiece (plus the drill's
breakthrough of a through hole), and a workingstep name is cut to what a comment line can hold.
Each refusal names the entity (#id), the attribute and the value as written; the valid value next
to it still plans.  Files are NIST's ex1 (tests/fixtures/iso14649) mutated by hand, with a
workpiece BLOCK added (the stock: X -10..150, Y -10..110, Z -30..5) so depths have a bottom."""
import math
import os
import re

import numpy as np
import pytest

from kezuri import post
from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, pockets_to_part21, PocketSpec, to_program
from kezuri.toolpath.ir.program import Tool

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = open(os.path.join(FIXTURES, "iso14649", "ex1.stp"), encoding="latin-1").read()
STOCK_BOTTOM = -30.0
# The 20 mm twist drill (#32: tool_top_angle 31 deg) passes a through hole's bottom by its point
# length 10 * tan(31 deg) = 6.009 mm plus 2 mm so its full diameter clears (workplan.drill_breakthrough).
BREAKTHROUGH = 10 * math.tan(math.radians(31)) + 2


def with_block(text: str = EX1) -> str:
    return text.replace("#4= WORKPIECE('SIMPLE WORKPIECE',#6,0.010,$,$,$,",
                        "#4= WORKPIECE('SIMPLE WORKPIECE',#6,0.010,$,$,#900,").replace(
        "#1= PROJECT(", "#900= BLOCK('STOCK',#901,160.,120.,35.);\n"
                        "#901= AXIS2_PLACEMENT_3D('STOCK',#902,#102,#103);\n"
                        "#902= CARTESIAN_POINT('',(-10.,-10.,-30.));\n#1= PROJECT(")


def edit(old: str, new: str, text: str | None = None) -> str:
    text = with_block() if text is None else text
    if re.match(r"#\d+= ", old):             # an instance line, not the commented-out original below it
        old, new = "\n" + old, "\n" + new
    assert text.count(old) == 1, old
    return text.replace(old, new)


def refusal(text: str) -> str:
    with pytest.raises(InputError) as caught:
        to_program(load_workplan(text))
    return str(caught.value)


def plans(text: str):
    program = to_program(load_workplan(text))
    assert [op.name for op in program.operations] == ["WS FINISH PLANAR FACE1", "WS DRILL HOLE1", "WS REAM HOLE1",
                                                      "WS ROUGH POCKET1", "WS FINISH POCKET1"]
    return program


def lowest(op) -> float:
    return float(np.min(op.xyz[:, 2]))


ROUGH = "$,$,$,#51,6.500,5.000,1.000,0.500);"          # axial, radial, allowance_side, allowance_bottom of #22


def test_the_fixture_with_its_block_plans():
    program = plans(with_block())
    assert lowest(program.operations[3]) == pytest.approx(STOCK_BOTTOM + 0.5)      # allowance_bottom 0.5 left


@pytest.mark.parametrize("attributes, name, value", [
    ("$,$,$,#51,6.500,5.000,1.000,-0.750);", "allowance_bottom", "-0.75"),
    ("$,$,$,#51,6.500,5.000,-2.25,0.500);", "allowance_side", "-2.25"),
])
def test_a_negative_allowance_is_refused_and_zero_plans(attributes, name, value):
    message = refusal(edit(ROUGH, attributes))
    assert f"#22 BOTTOM_AND_SIDE_ROUGH_MILLING: {name} {value} mm must be 0 or more" in message
    face = refusal(edit("#60,#61,#42,2.500,$);", "#60,#61,#42,2.500,-0.1);"))
    assert "#19 PLANE_FINISH_MILLING: allowance_bottom -0.1 mm must be 0 or more" in face
    program = plans(edit(ROUGH, attributes.replace(value, "0.")))
    if name == "allowance_bottom":      # no allowance: the roughing reaches the floor, and not below it
        assert lowest(program.operations[3]) == pytest.approx(STOCK_BOTTOM)


@pytest.mark.parametrize("value", ["0.", "-3.5", "-0."])
def test_an_axial_depth_not_above_zero_is_refused_and_a_small_one_plans(value):
    message = refusal(edit(ROUGH, f"$,$,$,#51,{value},5.000,1.000,0.500);"))
    shown = f"{float(value):g}"
    assert f"#22 BOTTOM_AND_SIDE_ROUGH_MILLING: axial_cutting_depth {shown} mm must be above 0" in message
    program = plans(edit(ROUGH, "$,$,$,#51,2.75,5.000,1.000,0.500);"))
    rough = program.operations[3]
    levels = sorted({round(float(z), 6) for z in rough.xyz[:, 2] if z < 0})
    # 29.5 mm to the floor (30 - 0.5) in steps of at most 2.75 mm: at least 11 levels, none deeper than the allowance
    assert len(levels) >= 11 and levels[0] == pytest.approx(STOCK_BOTTOM + 0.5)


@pytest.mark.parametrize("value", ["0.", "-1.25"])
def test_a_radial_depth_not_above_zero_is_refused_and_a_positive_one_plans(value):
    message = refusal(edit(ROUGH, f"$,$,$,#51,6.500,{value},1.000,0.500);"))
    assert f"#22 BOTTOM_AND_SIDE_ROUGH_MILLING: radial_cutting_depth {float(value):g} mm must be above 0" in message
    plans(edit(ROUGH, "$,$,$,#51,6.500,7.5,1.000,0.500);"))


@pytest.mark.parametrize("value", ["1.25", "0.", "-0.3", "40."])
def test_an_overlap_outside_zero_to_one_is_refused_and_a_ratio_plans(value):
    message = refusal(edit("#53= CONTOUR_PARALLEL(0.05,", f"#53= CONTOUR_PARALLEL({value},"))
    assert f"#53 CONTOUR_PARALLEL: overlap {float(value):g} must be above 0 and at most 1" in message
    face = refusal(edit("#42= BIDIRECTIONAL_MILLING(0.05,", f"#42= BIDIRECTIONAL_MILLING({value},"))
    assert f"#42 BIDIRECTIONAL_MILLING: overlap {float(value):g} must be above 0 and at most 1" in face
    plans(edit("#53= CONTOUR_PARALLEL(0.05,", "#53= CONTOUR_PARALLEL(0.95,"))


@pytest.mark.parametrize("value", ["0.", "-7.5"])
def test_a_hole_diameter_not_above_zero_is_refused(value):
    message = refusal(edit("#58= TOLERANCED_LENGTH_MEASURE(22.000,", f"#58= TOLERANCED_LENGTH_MEASURE({value},"))
    assert f"#58 TOLERANCED_LENGTH_MEASURE: diameter {float(value):g} mm must be above 0" in message


@pytest.mark.parametrize("drill, hole, refused", [("24.5", "22.000", True), ("20.000", "12.7", True),
                                                  ("22.000", "22.000", False), ("20.000", "25.", False)])
def test_a_drill_wider_than_its_hole_is_refused(drill, hole, refused):
    text = edit("#32= MILLING_TOOL_DIMENSION(20.000,", f"#32= MILLING_TOOL_DIMENSION({drill},")
    text = edit("#58= TOLERANCED_LENGTH_MEASURE(22.000,", f"#58= TOLERANCED_LENGTH_MEASURE({hole},", text)
    text = edit("#34= MILLING_TOOL_DIMENSION(22.000,", f"#34= MILLING_TOOL_DIMENSION({hole},", text)   # the reamer fits
    if not refused:
        plans(text)
        return
    message = refusal(text)
    assert "workingstep #11 'WS DRILL HOLE1'" in message
    assert (f"MILLING_CUTTING_TOOL #44 'SPIRAL_DRILL_20MM': diameter {float(drill):g} mm is larger than the "
            f"diameter {float(hole):g} mm of RoundHole #17 'HOLE1 D=22MM'") in message


@pytest.mark.parametrize("mill, refused", [("50.5", True), ("65.", True), ("36.", False)])
def test_an_end_mill_wider_than_its_pocket_is_refused(mill, refused):
    # The pocket #18 is 80 x 50 mm (#121, #122); the 18 mm end mill #39 also faces the planar face.
    text = edit("#30= MILLING_TOOL_DIMENSION(18.000,", f"#30= MILLING_TOOL_DIMENSION({mill},")
    if not refused:
        plans(text)
        return
    message = refusal(text)
    assert "workingstep #13 'WS ROUGH POCKET1'" in message
    assert (f"MILLING_CUTTING_TOOL #39 'MILL 18MM': diameter {float(mill):g} mm is larger than the width 50 mm of "
            "ClosedPocket #18 'POCKET1'") in message


@pytest.mark.parametrize("depth, refused", [("-4500.", True), ("-30.5", True), ("-29.", False)])
def test_a_hole_deeper_than_the_workpiece_is_refused(depth, refused):
    text = edit("#112= CARTESIAN_POINT('HOLE1: DEPTH ',(0.000,0.000,-30.000));",
                f"#112= CARTESIAN_POINT('HOLE1: DEPTH ',(0.000,0.000,{depth}));")
    if not refused:
        program = plans(text)
        assert lowest(program.operations[1]) == pytest.approx(float(depth) - BREAKTHROUGH, abs=1e-3)
        return
    message = refusal(text)
    assert f"ROUND_HOLE #17 'HOLE1 D=22MM': its depth reaches Z {float(depth):g}" in message.replace("RoundHole",
                                                                                                     "ROUND_HOLE")


@pytest.mark.parametrize("cutting_depth, refused", [("612.", True), ("38.5", True), ("0.", True), ("37.", False)])
def test_a_drilling_cutting_depth_past_the_breakthrough_is_refused(cutting_depth, refused):
    text = edit("#20= DRILLING($,$,'DRILL HOLE1',10.000,$,#44,#45,#41,$,$,",
                f"#20= DRILLING($,$,'DRILL HOLE1',10.000,$,#44,#45,#41,$,{cutting_depth},")
    if not refused:
        program = plans(text)
        assert lowest(program.operations[1]) == pytest.approx(-float(cutting_depth), abs=1e-3)
        return
    message = refusal(text)
    if float(cutting_depth) <= 0:
        assert "#20 DRILLING: cutting_depth 0 mm must be above 0" in message
    else:
        assert f"its cutting_depth {float(cutting_depth):g} reaches Z {-float(cutting_depth):g}" in message
        assert "workingstep #11 'WS DRILL HOLE1'" in message


def test_a_long_workingstep_name_is_cut_with_a_note_and_the_lines_fit_the_control():
    name = "ROUGH POCKET " + "\u00e9tape ".join(str(i) for i in range(6000))        # ~ 44,000 characters
    text = edit("#13= MACHINING_WORKINGSTEP('WS ROUGH POCKET1',", f"#13= MACHINING_WORKINGSTEP('{name}',")
    loaded = load_workplan(text)
    assert f"workingstep #13: its name is {len(name)} characters; the first 200 are used, followed by ..." \
        in loaded.warnings
    program = to_program(loaded)
    assert program.operations[3].name == name[:200] + "..."
    for post_name in ("linuxcnc", "fanuc", "grbl"):
        nc = post.milling_post(post_name).to_text(program)
        longest = max(len(line) for line in nc.splitlines())
        assert longest <= 252 and len(nc) < 60_000, (post_name, longest, len(nc))
    short = to_program(load_workplan(edit("#13= MACHINING_WORKINGSTEP('WS ROUGH POCKET1',",
                                          f"#13= MACHINING_WORKINGSTEP('{'N' * 200}',")))
    assert short.operations[3].name == "N" * 200 and not any("characters; the first" in n for n in short.notes)


def test_the_sample_plate_s_allowance_and_depth_attributes_are_checked_too():
    text = pockets_to_part21(((0, 0, -20), (120, 80, 0)),
                             [PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0)],
                             Tool(1, "flat", 6.0, flute_length=20.0), name="PLATE")
    plans_ok = to_program(load_workplan(text))
    assert plans_ok.operations
    rough = re.search(r"(#\d+)=\s*BOTTOM_AND_SIDE_ROUGH_MILLING\((.*?)\);", text, re.S)
    attributes = rough.group(2).split(",")
    attributes[-1] = "-0.125"                # allowance_bottom
    broken = text.replace(rough.group(0), f"{rough.group(1)}=BOTTOM_AND_SIDE_ROUGH_MILLING({','.join(attributes)});")
    message = refusal(broken)
    assert f"{rough.group(1)} BOTTOM_AND_SIDE_ROUGH_MILLING: allowance_bottom -0.125 mm must be 0 or more" in message


def test_the_new_messages_have_japanese_and_the_batch_refuses_by_name(tmp_path):
    import subprocess
    import sys
    cases = [edit(ROUGH, "$,$,$,#51,6.500,5.000,1.000,-0.750);"), edit(ROUGH, "$,$,$,#51,-1.,5.000,1.000,0.500);"),
             edit("#53= CONTOUR_PARALLEL(0.05,", "#53= CONTOUR_PARALLEL(2.5,"),
             edit("#32= MILLING_TOOL_DIMENSION(20.000,", "#32= MILLING_TOOL_DIMENSION(30.,"),
             edit("#30= MILLING_TOOL_DIMENSION(18.000,", "#30= MILLING_TOOL_DIMENSION(51.,")]
    messages = [refusal(text) for text in cases]
    messages += [w for w in load_workplan(edit("#13= MACHINING_WORKINGSTEP('WS ROUGH POCKET1',",
                                               f"#13= MACHINING_WORKINGSTEP('{'W' * 900}',")).warnings]
    bpy = pytest.importorskip("bpy")
    assert bpy
    from kezuri.operators import translations
    for message in messages:
        japanese = translations.japanese_message(message)
        assert japanese is not None and re.search(r"[\u3040-\u30ff\u4e00-\u9fff]", japanese), message
    source = tmp_path / "negative.stp"
    source.write_text(cases[0], encoding="latin-1")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    done = subprocess.run([sys.executable, os.path.join(root, "batch.py"), "stepnc", "--input", str(source),
                           "--out", str(tmp_path / "out")], capture_output=True, text=True, timeout=300, cwd=root)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr[-2000:]
    assert "#22 BOTTOM_AND_SIDE_ROUGH_MILLING: allowance_bottom -0.75 mm must be 0 or more" in done.stderr
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


@pytest.mark.parametrize("width, refused", [("8.5", True), ("9.99", True), ("10.000", False), ("14.", False)])
def test_an_end_mill_wider_than_its_slot_is_refused(width, refused):
    from test_stepnc_slot import slot_file
    text = slot_file().replace("#38= TOLERANCED_LENGTH_MEASURE(10.000,", f"#38= TOLERANCED_LENGTH_MEASURE({width},")
    if not refused:
        program = to_program(load_workplan(text))
        assert [op.name for op in program.operations][0] == "WS SLOT1"
        return
    message = refusal(text)
    assert "workingstep #60 'WS SLOT1'" in message
    assert (f"MILLING_CUTTING_TOOL #22 'ENDMILL 10MM': diameter 10 mm is larger than the width {float(width):g} mm "
            "of Slot #30 'SLOT1'") in message


# ex1's #46: DRILLING_TYPE_STRATEGY(0.75, 0.50, 2.000, 0.50, 0.75, 8.000) (NIST's note 12: ratios, once 0..100)
STRATEGY = "#46= DRILLING_TYPE_STRATEGY(0.75, 0.50, 2.000, 0.50,0.75, 8.000);"


@pytest.mark.parametrize("place, name, value", [(0, "reduced_cut_at_start", "75."), (1, "reduced_feed_at_start", "50."),
                                                (3, "reduced_cut_at_end", "1.5"), (4, "reduced_feed_at_end", "75.")])
def test_a_drilling_strategy_ratio_above_one_is_refused_not_read_as_percent(place, name, value):
    """ISO 14649-11 types the reductions positive_ratio_measure (0.5 for half of the programmed
    value): 50 is not read as 50 %, nor as a feed 50 times the programmed one."""
    values = ["0.75", "0.50", "2.000", "0.50", "0.75", "8.000"]
    values[place] = value
    message = refusal(edit(STRATEGY, f"#46= DRILLING_TYPE_STRATEGY({', '.join(values)});"))
    assert (f"#46 DRILLING_TYPE_STRATEGY: {name} {float(value):g} is above 1: it is a ratio of the programmed value "
            f"(0.5 for half), not a percentage; write {float(value) / 100:g} for {float(value):g} %") in message


def test_a_drilling_strategy_of_ratios_halves_the_feed_over_the_first_depth():
    """1 is allowed (no reduction); 0.5 of ex1's 1800 mm/min drilling feed is 900 over the first 2 mm."""
    program = plans(edit(STRATEGY, "#46= DRILLING_TYPE_STRATEGY(1., 0.5, 2.000, 1.,1., 8.000);"))
    drill = next(op for op in program.operations if op.name == "WS DRILL HOLE1")
    feeds = sorted(set(np.round(drill.feed[drill.kind == 1], 6)))
    assert feeds == [900.0, 1800.0]


def test_without_a_block_the_deepest_through_feature_sets_the_stock_bottom_and_the_notes_say_so():
    """NIST's ex1 as published has no BLOCK: its through hole #17 (Z 0 to -30) gives the stock's
    bottom.  A hole mistyped 4500 mm deep would make its own 4.5 m stock: planned as the file says
    (ISO 14649: a through feature goes through the workpiece), but never in silence."""
    notes = to_program(load_workplan(EX1)).notes
    assert ("no workpiece BLOCK: the stock bottom is taken as Z -30, the depth of the deepest through feature #17 "
            "'HOLE1 D=22MM' (30 mm below its top); check the stock's thickness, or give the workpiece its BLOCK") in notes
    deep = EX1.replace("#112= CARTESIAN_POINT('HOLE1: DEPTH ',(0.000,0.000,-30.000));",
                       "#112= CARTESIAN_POINT('HOLE1: DEPTH ',(0.000,0.000,-4500.));")
    # the pocket #18 made through too: it ends at its own depth, Z -30, far above the hole's bottom
    deep = deep.replace("#27= PLANAR_POCKET_BOTTOM_CONDITION();", "#27= THROUGH_POCKET_BOTTOM_CONDITION();")
    notes = to_program(load_workplan(deep)).notes
    assert any(note.startswith("no workpiece BLOCK: the stock bottom is taken as Z -4500, the depth of the deepest "
                               "through feature #17 'HOLE1 D=22MM' (4500 mm below its top)") for note in notes), notes
    assert [note for note in notes if note.startswith("through feature")] == [
        "through feature #18 'POCKET1' ends at Z -30, 4470 mm above that stock bottom: it does not go through"]
    # with its BLOCK the same hole is refused (test_a_hole_deeper_than_the_workpiece_is_refused), no note
    assert not any("no workpiece BLOCK" in note for note in to_program(load_workplan(with_block())).notes)
    bpy = pytest.importorskip("bpy")
    assert bpy
    from kezuri.operators import translations
    for note in [note for note in notes if "BLOCK" in note or note.startswith("through feature")]:
        japanese = translations.japanese_message(note)
        assert japanese is not None and "#1" in japanese and re.search(r"[\u3040-\u30ff\u4e00-\u9fff]", japanese), note
