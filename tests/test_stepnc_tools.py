"""STEP-NC tools as the file names them, and flat-bottomed holes a drill point cannot make.

ex1.stp (NIST's ISO 14649-11 example 1) with its tools renamed the way many generators name them
('T1 18 mm flat end mill', 'T2 20 mm drill', 'T3 22 mm reamer') and its first workingstep (the face,
cut with T1) made unsupported: the old numbering by first use gave the drill T1 and the end mill T3,
so an operator loading by the file's names drilled with the end mill.  Everything is read from the
NC text the posts write (the T words before M06, the header's TOOL and NOTE lines) and checked by
LinuxCNC's rs274 and the independent rules checker."""
import math
import re

import pytest

import controller_rules as rules
import rs274
from kezuri import post
from kezuri.toolpath.operations.stepnc.tools import number_in
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, skipped_workingsteps, to_program
from test_stepnc import add_instances, ex1_text, replace_instance

needs_rs274 = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")

MILL = "#39= MILLING_CUTTING_TOOL('T1 18 mm flat end mill',#29,(#125),80.000,$,$);"
DRILL = "#44= MILLING_CUTTING_TOOL('T2 20 mm drill',#31,(#126),90.000,$,$);"
REAMER = "#47= MILLING_CUTTING_TOOL('T3 22 mm reamer',#33,(#127),100.000,$,$);"
# A strategy the reader does not plan: the face's workingstep #10 (T1) is skipped when the file is read.
SPIRAL_FACE = "#42= CONTOUR_SPIRAL(0.05,.T.,.CW.,.CLIMB.);"


def named_tools(mill=MILL, drill=DRILL, reamer=REAMER, skip_face=True) -> str:
    text = replace_instance(ex1_text(), 39, mill)
    text = replace_instance(text, 44, drill)
    text = replace_instance(text, 47, reamer)
    return replace_instance(text, 42, SPIRAL_FACE) if skip_face else text


def header_notes(text: str) -> list:
    """The NOTE comments of an NC header, wrapped lines joined back."""
    notes = []
    for line in text.splitlines():
        if line.startswith("(NOTE: "):
            notes.append(line[len("(NOTE: "):-1])
        elif line.startswith("(  ") and notes:
            notes[-1] += " " + line[3:-1]
    return notes


def loaded_tools(text: str) -> list:
    """The T number of every M06 in program order (LinuxCNC: 'Tn M06')."""
    return [int(t) for t in re.findall(r"^T(\d+) M06$", text, re.MULTILINE)]


def operation_tool(text: str) -> dict:
    """{operation name: T number} from the header's OPERATION lines."""
    return {name: int(t) for name, t in re.findall(r"^\(OPERATION: (.*) - T(\d+) - ", text, re.MULTILINE)}


def test_identifiers_that_state_a_tool_number():
    assert [number_in(s) for s in ("2", "T2", "T02", "t2 5 mm drill", "TOOL 2", "Tool #2", "T-2", " 7 ")] == \
        [2, 2, 2, 2, 2, 2, 2, 7]
    # sizes and names are not tool numbers
    assert [number_in(s) for s in ("MILL 18MM", "6 mm end mill", "T10MM", "T2.5", "TAP M6", "", "REAMER_22MM")] == \
        [None] * 7


def test_the_file_names_the_t_numbers_even_after_a_skipped_workingstep():
    loaded = load_workplan(named_tools())
    assert [s.id for s in loaded.workingsteps] == [11, 12, 13, 14]          # #10 (the face, T1) left out
    program = to_program(loaded)
    text = post.milling_post("linuxcnc").to_text(program)
    # the drill is the file's T2, the reamer T3, the end mill T1: not 1, 2, 3 by first use
    assert loaded_tools(text) == [2, 3, 1]
    assert operation_tool(text) == {"WS DRILL HOLE1": 2, "WS REAM HOLE1": 3, "WS ROUGH POCKET1": 1,
                                    "WS FINISH POCKET1": 1}
    tools = re.findall(r"^\(TOOL: (T\d+) .*\[(.*)\]\)$", text, re.MULTILINE)
    assert sorted(tools) == [("T1", "T1 18 MM FLAT END MILL"), ("T2", "T2 20 MM DRILL"), ("T3", "T3 22 MM REAMER")]
    assert not any("numbered in order of first use" in n.lower() for n in header_notes(text))
    # the skipped workingstep is named with its reason in the header, the program's notes and the report list
    assert any(n.startswith("WORKINGSTEP #10 'WS FINISH PLANAR FACE1' SKIPPED: CONTOUR_SPIRAL #42")
               for n in header_notes(text))
    assert [(s["id"], s["name"]) for s in skipped_workingsteps(program.notes)] == [(10, "WS FINISH PLANAR FACE1")]
    for name, control in (("linuxcnc", "linuxcnc"), ("fanuc", "fanuc-mill"), ("grbl", "grbl")):
        assert rules.check(post.milling_post(name).to_text(program), control) == [], name


@needs_rs274
def test_rs274_loads_the_files_tool_numbers():
    program = to_program(load_workplan(named_tools()))
    calls = rs274.run(post.milling_post("linuxcnc").to_text(program))
    selected = [int(float(args[0])) for name, args in calls if name == "SELECT_TOOL"]
    assert selected == [2, 3, 1]


def test_names_without_numbers_are_numbered_by_first_use_and_said_so():
    text = post.milling_post("fanuc").to_text(to_program(load_workplan(ex1_text())))   # 'MILL 18MM' ...
    assert [int(t) for t in re.findall(r"^T(\d+) M06$", text, re.MULTILINE)] == [1, 2, 3, 1]
    assert ("TOOLS WITHOUT A USABLE NUMBER IN THEIR IDENTIFIER, NUMBERED IN ORDER OF FIRST USE: T1 'MILL 18MM', "
            "T2 'SPIRAL_DRILL_20MM', T3 'REAMER_22MM'") in header_notes(text)


def test_two_tools_claiming_one_number_are_told_apart():
    # the reamer says T2 too: the drill (first in the workplan) keeps T2, the reamer gets the lowest free number
    text_in = named_tools(reamer="#47= MILLING_CUTTING_TOOL('T2 22 mm reamer',#33,(#127),100.000,$,$);",
                          skip_face=False)
    program = to_program(load_workplan(text_in))
    text = post.milling_post("linuxcnc").to_text(program)
    assert operation_tool(text) == {"WS FINISH PLANAR FACE1": 1, "WS DRILL HOLE1": 2, "WS REAM HOLE1": 3,
                                    "WS ROUGH POCKET1": 1, "WS FINISH POCKET1": 1}
    notes = header_notes(text)
    assert ("#47 MILLING_CUTTING_TOOL 'T2 22 MM REAMER' AND #44 'T2 20 MM DRILL' BOTH CLAIM T2 BUT ARE DIFFERENT "
            "TOOLS [IDENTIFIER, BODY OR DIMENSIONS]: #44 KEEPS T2") in notes
    assert ("TOOLS WITHOUT A USABLE NUMBER IN THEIR IDENTIFIER, NUMBERED IN ORDER OF FIRST USE: "
            "T3 'T2 22 MM REAMER'") in notes


def test_a_number_no_control_takes_is_replaced_and_said_so():
    text_in = named_tools(mill="#39= MILLING_CUTTING_TOOL('T0 18 mm flat end mill',#29,(#125),80.000,$,$);",
                          skip_face=False)
    program = to_program(load_workplan(text_in))
    assert {op.name: op.tool.number for op in program.operations}["WS ROUGH POCKET1"] == 1   # 1 is free
    assert any("names T0, not a tool number every control takes (1..9999)" in n for n in program.notes)


# --------------------------------------------------------------------------- flat-bottomed holes


def flat_hole(extra_steps: str = "") -> str:
    """ex1 with HOLE1 a blind 22 mm hole 20 deep with a FLAT_HOLE_BOTTOM, drilled (20 mm, 118 degree point)
    and reamed."""
    text = replace_instance(ex1_text(), 26, "#26= FLAT_HOLE_BOTTOM();")
    text = replace_instance(text, 112, "#112= CARTESIAN_POINT('HOLE1: DEPTH ',(0.000,0.000,-20.000));")
    if extra_steps:
        text = text.replace("#2= WORKPLAN('MAIN WORKPLAN',(#10,#11,#12,#13,#14),",
                            f"#2= WORKPLAN('MAIN WORKPLAN',(#10,#11,#12,{extra_steps}#13,#14),")
    return text


def test_a_flat_bottom_drilled_with_a_point_is_named_with_its_cone():
    program = to_program(load_workplan(flat_hole()))
    text = post.milling_post("linuxcnc").to_text(program)
    cone = 10.0 * math.tan(math.radians(31.0))          # the 20 mm drill's point (tool_top_angle 31)
    wanted = (f"ROUND_HOLE #17 'HOLE1 D=22MM' HAS A FLAT_HOLE_BOTTOM BUT WORKINGSTEP #11 'WS DRILL HOLE1' DRILLS IT "
              f"WITH A 118 DEGREE POINT: THE TIP STOPS AT THE DEPTH [Z -20] AND LEAVES A CONE {cone:.3f} MM HIGH "
              f"[THE FULL DIAMETER REACHES Z {-20 + cone:.3f}]; NO WORKINGSTEP CUTS THE BOTTOM FLAT")
    assert any(n.startswith(wanted) for n in header_notes(text))
    # the drill stops with its tip at the depth: nothing deeper is cut to hide the cone
    calls = rs274.run(text) if rs274.available() else None
    if calls is not None:
        kinds, points, _ = rs274.motion_endpoints(calls)
        at_hole = (abs(points[:, 0] - 20.0) < 1e-6) & (abs(points[:, 1] - 60.0) < 1e-6)   # HOLE1's axis
        assert points[at_hole, 2].min() == pytest.approx(-20.0, abs=1e-4)


def test_a_flat_end_mill_finishing_the_hole_makes_it_flat():
    mill = ("#300= MACHINING_WORKINGSTEP('WS MILL HOLE1 BOTTOM',#62,#17,#301,$);",
            "#301= BOTTOM_AND_SIDE_FINISH_MILLING($,$,'MILL HOLE1',10.000,$,#302,#50,#41,$,$,$,$,2.0,$,$,$);",
            "#302= MILLING_CUTTING_TOOL('T4 10 mm end mill',#303,(#125),80.000,$,$);",
            "#303= ENDMILL(#304,4,.RIGHT.,.F.,$);", "#304= MILLING_TOOL_DIMENSION(10.000,$,$,25.0,0.0,$,$);")
    text = add_instances(flat_hole("#300,"), *mill)
    text = text.replace("#17= ROUND_HOLE('HOLE1 D=22MM',#4,(#20,#21),", "#17= ROUND_HOLE('HOLE1 D=22MM',#4,(#20,#21,#301),")
    program = to_program(load_workplan(text))
    assert "WS MILL HOLE1 BOTTOM" in [op.name for op in program.operations]
    assert not any("FLAT_HOLE_BOTTOM" in n for n in program.notes)


def test_the_toolpath_picture_captions_what_was_not_cut():
    from kezuri.toolpath.pictures import picture_jobs
    from kezuri.toolpath.simulate import BoxStock

    loaded = load_workplan(named_tools())
    program = to_program(loaded)
    skipped = skipped_workingsteps(program.notes)
    caption = "NOT CUT: " + ", ".join(f"#{s['id']} {s['name']}" for s in skipped)
    picture = picture_jobs.toolpath_picture(program.operations, BoxStock(0, 0, -30, 100, 120, 5), caption=caption,
                                            size=(600, 400))
    assert "NOT CUT: #10 WS FINISH PLANAR FACE1" in picture.texts
    long = picture_jobs.toolpath_picture(program.operations, BoxStock(0, 0, -30, 100, 120, 5),
                                         caption="NOT CUT: " + "#10 X, " * 200, size=(600, 400))
    shown = [t for t in long.texts if t.startswith("NOT CUT")][0]
    assert shown.endswith("...") and picture_jobs.text_width(shown) <= 600 - 24
